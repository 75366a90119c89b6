"""Open-loop action error of checkpoints on held-out expert episodes, split by the episode's subtask
(the annotation ``subtask_index``): where in a task a policy's predicted chunks leave the expert's.

    python benchmarks/open_loop_by_phase.py --repo-id local/cpu_count_heldout \\
        --root outputs/datasets/cpu_count_heldout RUN_A/checkpoints/005000/pretrained_model RUN_B/...

Prints, per checkpoint and subtask, the mean absolute error of the whole predicted 16-step chunk
against the recorded one (normalised units undone: radians, gripper 0-1), for the arms, the
grippers and the view (torso yaw, head pitch), over every frame of the held-out set.
"""

from __future__ import annotations

import argparse
import json
from collections import defaultdict
from pathlib import Path

import numpy as np
import torch

from lerobot_activearena.eval.learning_curve import GROUPS


def by_phase(policy_dir: Path, repo_id: str, root: Path) -> dict[int, dict[str, float]]:
    from lerobot.configs.policies import PreTrainedConfig
    from lerobot.datasets.factory import resolve_delta_timestamps
    from lerobot.datasets.lerobot_dataset import LeRobotDataset, LeRobotDatasetMetadata
    from lerobot.policies import make_policy, make_pre_post_processors

    from lerobot_activearena.eval.protocol import register_policy_types

    register_policy_types()
    cfg = PreTrainedConfig.from_pretrained(policy_dir)
    cfg.pretrained_path, cfg.device = Path(policy_dir), "cpu"
    meta = LeRobotDatasetMetadata(repo_id, root=root)
    policy = make_policy(cfg, ds_meta=meta).eval()
    pre, post = make_pre_post_processors(cfg, pretrained_path=cfg.pretrained_path)
    ds = LeRobotDataset(repo_id, root=root, delta_timestamps=resolve_delta_timestamps(cfg, meta))
    loader = torch.utils.data.DataLoader(ds, batch_size=16, shuffle=False, num_workers=0)
    sums: dict[int, np.ndarray] = defaultdict(lambda: np.zeros(18))
    counts: dict[int, np.ndarray] = defaultdict(lambda: np.zeros(18))
    with torch.no_grad():
        for batch in loader:
            obs = {k: v for k, v in batch.items() if k.startswith("observation.") and k in cfg.input_features}
            obs["task"] = batch["task"]
            obs.update(
                {k: v for k, v in batch.items() if k.startswith("observation.") and k.endswith("_is_pad")}
            )
            pred = post(policy.predict_action_chunk(pre(obs))).cpu().numpy()
            target, pad = batch["action"].numpy(), batch["action_is_pad"].numpy()
            steps = min(pred.shape[1], target.shape[1])
            err = np.abs(pred[:, :steps] - target[:, :steps]) * ~pad[:, :steps, None]
            for b, phase in enumerate(batch["subtask_index"].reshape(-1).tolist()):
                sums[phase] += err[b].sum(0)
                counts[phase] += (~pad[b, :steps]).sum() * np.ones(18)
    return {
        phase: {name: float((sums[phase][idx] / counts[phase][idx]).mean()) for name, idx in GROUPS.items()}
        | {"frames": int(counts[phase][0] // 16)}
        for phase in sorted(sums)
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("checkpoints", nargs="+", type=Path)
    p.add_argument("--repo-id", required=True)
    p.add_argument("--root", type=Path, required=True)
    args = p.parse_args()
    for ckpt in args.checkpoints:
        for phase, row in by_phase(ckpt, args.repo_id, args.root).items():
            print(json.dumps({"checkpoint": str(ckpt), "subtask": phase, **row}))


if __name__ == "__main__":
    main()
