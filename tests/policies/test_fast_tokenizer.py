"""The FAST run's action tokenizer: DCT codes in the documented order, a BPE fitted on a builder
dataset's chunks by `activearena-fit-fast-tokenizer`, saved and reloaded unchanged, round trips
within the quantisation error, and sequences that spell no chunk decoded as None."""

import json

import numpy as np
import pytest
from helpers.params import DATASET_REPO

from lerobot_activearena.cli.fit_fast_tokenizer import action_chunks, fit
from lerobot_activearena.policies.activearena_fast.action_tokenizer import FastActionTokenizer, dct_matrix


def _smooth_chunks(n=300, seed=0):
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 1, 16)[None, :, None]
    start, slope = rng.uniform(-0.8, 0.8, (n, 1, 18)), rng.uniform(-0.2, 0.2, (n, 1, 18))
    return start + slope * t


def test_codes_are_the_scaled_dct_flattened_frequency_major():
    m = dct_matrix(16)
    np.testing.assert_allclose(m @ m.T, np.eye(16), atol=1e-12)  # orthonormal
    tok = FastActionTokenizer.fit(_smooth_chunks(), vocab_size=400)
    chunk = _smooth_chunks(1, seed=3)[0]
    codes = tok.codes(chunk)
    assert codes.shape == (288,) and codes.dtype == np.int64
    # the first 18 codes: every dimension's DC term (sum / 4 for an orthonormal 16-point DCT) x 10
    np.testing.assert_array_equal(codes[:18], np.rint(chunk.sum(axis=0) / 4 * 10))
    np.testing.assert_allclose(tok.chunk(codes), chunk, atol=0.05 * 4)  # rounding: 0.05 per coefficient
    with pytest.raises(ValueError, match="a chunk is"):
        tok.codes(chunk[:8])
    with pytest.raises(ValueError, match="below the smallest"):
        tok.encode(chunk - 50.0)


def test_fitted_on_a_builder_dataset_saves_reloads_and_round_trips(bell_count_dataset, tmp_path, capsys):
    out = tmp_path / "fast"
    argv = ["--repo-id", DATASET_REPO, "--root", str(bell_count_dataset), "--out", str(out)]
    report = fit([*argv, "--vocab-size", "400", "--holdout", "2"])
    printed = capsys.readouterr().out
    assert "tokens per chunk" in printed and "failed decodes" in printed
    assert json.loads((out / "fit_report.json").read_text()) == report
    held = report["held_out"]
    assert held["decode_failures"] == 0 and held["chunks"] > 0
    assert held["tokens_per_chunk_mean"] < 288 / 4, held  # BPE compresses the codes
    assert held["abs_error_mean"] < 0.02, held

    tok = FastActionTokenizer.from_pretrained(out)
    assert tok.vocab_size <= 400 and (tok.horizon, tok.action_dim, tok.scale) == (16, 18, 10.0)
    chunk = np.clip(_smooth_chunks(1, seed=5)[0], -1, 1)
    ids = tok.encode(chunk)
    assert ids == FastActionTokenizer.from_pretrained(out).encode(chunk)  # the files fix the tokenizer
    np.testing.assert_allclose(tok.decode(ids), tok.chunk(tok.codes(chunk)), atol=1e-9)
    assert tok.decode(ids[:-1]) is None  # a cut sequence spells no chunk
    assert tok.decode([tok.vocab_size + 5]) is None

    with pytest.raises(SystemExit):  # an existing tokenizer is not overwritten silently
        fit(argv)
    assert "--overwrite" in capsys.readouterr().err
    with pytest.raises(FileNotFoundError, match="activearena-fit-fast-tokenizer"):
        FastActionTokenizer.from_pretrained(tmp_path / "nothing")


def test_chunks_repeat_the_last_action_past_an_episode_end():
    actions = np.arange(20, dtype=float)[:, None].repeat(18, axis=1)
    episodes = np.array([0] * 12 + [1] * 8)
    chunks = action_chunks(actions, episodes)
    assert chunks.shape == (20, 16, 18)
    np.testing.assert_array_equal(chunks[10, :, 0], [10, 11] + [11] * 14)  # episode 0 ends at frame 11
    np.testing.assert_array_equal(chunks[12, :3, 0], [12, 13, 14])  # episode 1 starts fresh
