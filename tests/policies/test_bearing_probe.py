"""analysis/policies/bearing_probe.py: the rows it reads from a vision table and its ridge fit."""

import numpy as np
import torch
from helpers.analysis_scripts import load
from safetensors.torch import save_file


def test_features_reads_each_frames_embeddings_then_deepstack(tmp_path):
    """Frames in runs and alone come back in the asked order, each its tokens' embeddings then the
    deepstack layers' features, flattened."""
    script = load("analysis/policies/bearing_probe.py")
    embeds = torch.arange(10 * 2 * 3, dtype=torch.float32).reshape(10, 2, 3)
    deep = -torch.arange(2 * 10 * 2 * 3, dtype=torch.float32).reshape(2, 10, 2, 3)
    cache = tmp_path / "table.safetensors"
    save_file({"embeds": embeds, "deepstack": deep}, str(cache))
    index = np.array([2, 3, 4, 7])
    rows = script.features(cache, index)
    expected = [np.concatenate([embeds[i].ravel(), deep[:, i].ravel()]) for i in index]
    np.testing.assert_array_equal(rows, np.stack(expected))


def test_ridge_recovers_a_linear_bearing():
    """With a small penalty the fit gives back the weights and offset the bearings were made with."""
    script = load("analysis/policies/bearing_probe.py")
    rng = np.random.default_rng(0)
    x, w = rng.normal(size=(200, 6)), rng.normal(size=6)
    fit, offset = script.ridge(x, x @ w + 5.0, alpha=1e-6)
    np.testing.assert_allclose(fit, w, atol=1e-6)
    assert abs(offset - 5.0) < 1e-6
