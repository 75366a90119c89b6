"""Where a training sample's compute goes: the forward FLOPs of a policy preset, split by module
(vision tower, language model, action head, ...), beside ACT's CPU preset on the same dataset.

    python analysis/policies/compute_split.py --root outputs/datasets/cpu_click_bell_200_vla \\
        --repo-id local/cpu_click_bell_200 configs/policy/small/oft_subtask_action_12_ws.json

Builds each policy with LeRobot's factories from the preset's ``policy`` block, draws one sample (the
middle frame of the middle episode) with the preset's delta timestamps, and counts the forward's
FLOPs with torch's ``FlopCounterMode`` (matrix multiplies and convolutions; a backward costs about
twice the forward). Prints FLOPs per sample by module, and the vision tower's per frame (ACT's
ResNet18 reads one frame a sample).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import torch
from lerobot.configs.policies import PreTrainedConfig
from lerobot.datasets.dataset_metadata import LeRobotDatasetMetadata
from lerobot.datasets.factory import resolve_delta_timestamps
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.policies.factory import make_policy, make_pre_post_processors
from torch.utils.flop_counter import FlopCounterMode

import lerobot_activearena.policies.activearena_oft  # noqa: F401  (registers activearena_oft)

ACT = "configs/policy/baselines/act_cpu.json"


def policy_config(path: str) -> PreTrainedConfig:
    block = dict(json.loads(Path(path).read_text())["policy"])
    kind = block.pop("type")
    return PreTrainedConfig.get_choice_class(kind)(**block)


def forward_flops(cfg: PreTrainedConfig, root: Path, repo_id: str, depth: int) -> tuple[dict[str, int], int]:
    """FLOPs of one sample's forward by module name (``Global``: all), and the frames the vision
    tower encoded."""
    meta = LeRobotDatasetMetadata(repo_id, root=root)
    policy = make_policy(cfg, ds_meta=meta)
    pre, _ = make_pre_post_processors(cfg, dataset_stats=meta.stats)
    ds = LeRobotDataset(
        repo_id, root=root, video_backend="pyav", delta_timestamps=resolve_delta_timestamps(cfg, meta)
    )
    episode = meta.episodes[meta.total_episodes // 2]  # its middle frame: some memory frames
    sample = ds[(episode["dataset_from_index"] + episode["dataset_to_index"]) // 2]
    batch = {k: (v.unsqueeze(0) if isinstance(v, torch.Tensor) else [v]) for k, v in sample.items()}
    policy.train()
    images = []  # the frames each vision-tower call encodes (Qwen3-VL's grid_thw rows)
    for module in policy.modules():
        if type(module).__name__.endswith("VisionModel"):
            module.register_forward_hook(
                lambda m, args, kwargs, out: images.append(len(kwargs.get("grid_thw", args[-1]))),
                with_kwargs=True,
            )
    counter = FlopCounterMode(display=False, depth=depth)
    with counter:
        policy.forward(pre(batch))
    counts = {name: sum(ops.values()) for name, ops in counter.get_flop_counts().items()}
    return counts, sum(images)


def vision_flops(counts: dict[str, int]) -> int:
    """The vision tower's share of ``forward_flops``' counts (0 for ACT, whose ResNet is its own)."""
    return sum(n for name, n in counts.items() if "." not in name and "Vision" in name)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("presets", nargs="+", help="preset JSONs (configs/policy/...)")
    p.add_argument("--root", type=Path, required=True)
    p.add_argument("--repo-id", required=True)
    p.add_argument("--vlm-path", help="replaces the VLA presets' vlm_path (e.g. a wider vision tower)")
    p.add_argument("--depth", type=int, default=3, help="module depth of the split (1: the policy)")
    args = p.parse_args()
    torch.manual_seed(0)
    for preset in [ACT, *args.presets]:
        cfg = policy_config(preset)
        cfg.device = "cpu"
        if args.vlm_path and hasattr(cfg, "vlm_path"):
            cfg.vlm_path = args.vlm_path
        counts, images = forward_flops(cfg, args.root, args.repo_id, args.depth)
        total = counts.pop("Global", 0)
        print(f"\n{preset}: {total / 1e9:.3f} GFLOP forward per sample")
        vision = vision_flops(counts)
        if images:
            print(
                f"  vision tower: {vision / 1e9:.3f} GFLOP on {images} frames, {vision / images / 1e9:.3f} a frame"
            )
        level = {name: n for name, n in counts.items() if name.count(".") == args.depth - 1}
        for name, n in sorted(level.items(), key=lambda kv: -kv[1]):
            if n >= 0.005 * total:
                print(f"  {n / 1e9:8.3f} GFLOP  {100 * n / total:5.1f} %  {name}")


if __name__ == "__main__":
    main()
