"""The learning curve reads a checkpoint in a fresh process, as its CLI does."""

import subprocess
import sys

from lerobot.configs.types import FeatureType, PolicyFeature
from lerobot.policies.act.configuration_act import ACTConfig


def test_a_checkpoints_image_size_is_read_in_a_fresh_process(tmp_path):
    """A checkpoint's config names its policy type; a fresh process (the CLI's) must have LeRobot's
    types registered before reading it."""
    cfg = ACTConfig(device="cpu")
    cfg.input_features = {
        "observation.images.head": PolicyFeature(FeatureType.VISUAL, (3, 96, 128)),
        "observation.state": PolicyFeature(FeatureType.STATE, (18,)),
    }
    cfg.output_features = {"action": PolicyFeature(FeatureType.ACTION, (18,))}
    cfg.save_pretrained(tmp_path)
    code = (
        "import sys; from pathlib import Path; "
        "from lerobot_activearena.eval.learning_curve import image_size; print(image_size(Path(sys.argv[1])))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code, str(tmp_path)], capture_output=True, text=True, timeout=300
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split()[-2:] == ["(96,", "128)"]
