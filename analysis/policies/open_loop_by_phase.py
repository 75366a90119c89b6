"""Open-loop action error of checkpoints on held-out expert episodes, split by the episode's subtask
(the annotation ``subtask_index``): where in a task a policy's predicted chunks leave the expert's.

    python analysis/policies/open_loop_by_phase.py --repo-id local/cpu_count_heldout \\
        --root outputs/datasets/cpu_count_heldout RUN_A/checkpoints/005000/pretrained_model RUN_B/...

Prints, per checkpoint and subtask, the mean absolute error of the whole predicted 16-step chunk
against the recorded one (normalised units undone: radians, gripper 0-1), for the arms, the
grippers and the view (torso yaw, head pitch), over every frame of the held-out set.
``--memory-ablation blank`` (or ``drop``): the same with the memory frames gray (or left out), where a
phase leans on what the policy saw before.
"""

from __future__ import annotations

import argparse
import json
from collections import defaultdict
from pathlib import Path

import numpy as np

from lerobot_activearena.eval.learning_curve import GROUPS, chunk_errors
from lerobot_activearena.eval.protocol import register_policy_types


def by_phase(
    policy_dir: Path, repo_id: str, root: Path, memory_ablation: str = "none"
) -> dict[int, dict[str, float]]:
    sums: dict[int, np.ndarray] = defaultdict(lambda: np.zeros(18))
    counts: dict[int, np.ndarray] = defaultdict(lambda: np.zeros(18))
    for batch, err, valid in chunk_errors(policy_dir, repo_id, root, 16, memory_ablation):
        for b, phase in enumerate(batch["subtask_index"].reshape(-1).tolist()):
            sums[phase] += err[b].sum(0)
            counts[phase] += valid[b].sum() * np.ones(18)
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
    p.add_argument(
        "--memory-ablation",
        choices=["none", "blank", "drop"],
        default="none",
        help="blank: the memory frames reach the policy as gray images; drop: none reach it, as at an "
        "episode's first frame (--policy.memory_ablation)",
    )
    args = p.parse_args()
    register_policy_types()
    for ckpt in args.checkpoints:
        for phase, row in by_phase(ckpt, args.repo_id, args.root, args.memory_ablation).items():
            print(
                json.dumps(
                    {
                        "checkpoint": str(ckpt),
                        "memory_ablation": args.memory_ablation,
                        "subtask": phase,
                        **row,
                    }
                )
            )


if __name__ == "__main__":
    main()
