"""Snapshot a tiny ``activearena_oft`` checkpoint and what it does, so a later change of the policy code
can be held against it (``tests/policies/test_saved_checkpoints.py``). Run once, before such a change:

    PYTHONPATH=tests python -m helpers.saved_oft tests/policies/fixtures/oft_saved_<date>

It writes ``tiny_qwen3_vl/`` (the random backbone), ``checkpoint/`` (policy, pre- and postprocessor as
``save_pretrained`` writes them) and ``expected_actions.safetensors`` (34 steps of ``select_action`` on
``inputs()``: three chunks, so the memory bank is written and read)."""

import sys
from pathlib import Path

import torch
from safetensors.torch import save_file

STEPS, TASK = 34, "click the bell"


def inputs(steps: int = STEPS):
    """The raw observations, the same on every machine (torch's CPU generator)."""
    g = torch.Generator().manual_seed(1)
    for _ in range(steps):
        yield {
            "observation.images.head": torch.rand(1, 3, 96, 128, generator=g),
            "observation.state": torch.rand(1, 18, generator=g) - 0.5,
            "task": [TASK],
        }


def main(out: Path) -> None:
    from lerobot.configs.types import FeatureType, PolicyFeature
    from lerobot.policies.factory import make_pre_post_processors

    import lerobot_env_activearena  # noqa: F401  (registers the policy types)
    from lerobot_activearena.policies.activearena_oft.configuration_activearena_oft import (
        ActiveArenaOFTConfig,
    )
    from lerobot_activearena.policies.activearena_oft.modeling_activearena_oft import ActiveArenaOFTPolicy
    from lerobot_activearena.policies.activearena_vla.tiny_vlm import make_tiny_vlm

    out.mkdir(parents=True, exist_ok=True)
    vlm = make_tiny_vlm(out / "tiny_qwen3_vl", texts=[TASK, "press the button"])
    cfg = ActiveArenaOFTConfig(
        vlm_path=str(vlm),
        device="cpu",
        state_hidden=32,
        memory="chunk",
        history=2,
        think="none",
        input_features={
            "observation.images.head": PolicyFeature(FeatureType.VISUAL, (3, 96, 128)),
            "observation.state": PolicyFeature(FeatureType.STATE, (18,)),
        },
        output_features={"action": PolicyFeature(FeatureType.ACTION, (18,))},
    )
    unit = {"mean": torch.zeros(18), "std": torch.ones(18), "min": -torch.ones(18), "max": torch.ones(18)}
    torch.manual_seed(0)
    policy = ActiveArenaOFTPolicy(cfg)
    pre, post = make_pre_post_processors(cfg, dataset_stats={"observation.state": unit, "action": unit})
    for part in (policy, pre, post):
        part.save_pretrained(out / "checkpoint")
    policy.reset()
    actions = torch.cat([policy.select_action(pre(raw)) for raw in inputs()])
    save_file({"actions": actions}, out / "expected_actions.safetensors")


if __name__ == "__main__":
    main(Path(sys.argv[1]))
