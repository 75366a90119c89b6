"""Checkpoints saved by earlier code keep loading and acting the same: a tiny ``activearena_oft``
checkpoint snapshotted before the policy seams were made public (``tests/helpers/saved_oft.py``)."""

from pathlib import Path

import torch
from helpers.saved_oft import inputs
from lerobot.configs.policies import PreTrainedConfig
from lerobot.policies.factory import get_policy_class, make_pre_post_processors
from safetensors.torch import load_file

SAVED = Path(__file__).parent / "fixtures" / "oft_saved_2026_11_25"


def test_an_oft_checkpoint_saved_before_the_refactor_loads_and_acts_the_same():
    ckpt, vlm = SAVED / "checkpoint", str(SAVED / "tiny_qwen3_vl")
    cfg = PreTrainedConfig.from_pretrained(ckpt)
    cfg.vlm_path, cfg.device = vlm, "cpu"  # the checkpoint moved: its backbone is found by path
    policy = get_policy_class(cfg.type).from_pretrained(ckpt, config=cfg).eval()
    pre, _ = make_pre_post_processors(
        cfg,
        pretrained_path=str(ckpt),
        preprocessor_overrides={"activearena_oft_vlm_inputs": {"vlm_path": vlm}},
    )
    policy.reset()
    actions = torch.cat([policy.select_action(pre(raw)) for raw in inputs()])
    expected = load_file(SAVED / "expected_actions.safetensors")["actions"]
    assert actions.shape == expected.shape == (34, 18)
    torch.testing.assert_close(actions, expected, rtol=1e-4, atol=1e-5)
