"""Does a state-conditioned policy read the image or its state? A swap probe on training frames.

    python analysis/policies/state_swap_probe.py --repo-id local/cpu_click_bell_200 \\
        --root outputs/datasets/cpu_click_bell_200_vla --frames 40,50,72 CHECKPOINT...

For random pairs of training episodes (A, B) at the same frame index, the policy sees A's images (the
current frame and its memory) with B's states (the current state and the memory frames' states).
Printed per frame index, over the pairs: the left arm's mean absolute error (rad) of the predicted
chunk against A's recorded chunk (the image's) and against B's (the state's), the unswapped
prediction's error against A's, and the separation of A's and B's recorded chunks. A policy that
moves the arm where the image shows the target follows A; one that continues its state's motion
follows B.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
from pathlib import Path

import numpy as np
import torch

from lerobot_activearena.cli.args import int_ranges

_SPEC = importlib.util.spec_from_file_location(
    "training_scenes", Path(__file__).with_name("training_scenes.py")
)
training_scenes = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(training_scenes)
LEFT_ARM = training_scenes.LEFT_ARM


def swap_errors(scenes, frame: int, pairs: int, episodes: list[int], seed: int = 0) -> np.ndarray:
    """(pairs, 4): the swapped prediction's left-arm error against A's and B's recorded chunks, the
    unswapped prediction's against A's, and A-B separation; episodes with ``frame`` + 16 frames."""
    from lerobot_activearena.eval.learning_curve import policy_inputs

    long_enough = [e for e in episodes if len(scenes.frames(e)) > frame + 16]
    if len(long_enough) < 2:
        raise SystemExit(f"fewer than 2 of the episodes have {frame + 16} frames: choose an earlier --frames")

    def sample(ep: int) -> dict:
        item = scenes.ds[scenes.frames(ep)[frame]]
        return {k: v[None] if isinstance(v, torch.Tensor) else [v] for k, v in item.items()}

    @torch.no_grad()
    def predict(batch: dict) -> np.ndarray:
        return scenes.post(scenes.policy.predict_action_chunk(scenes.pre(policy_inputs(batch, scenes.cfg))))

    rng, rows = np.random.default_rng(seed), []
    for _ in range(pairs):
        a, b = rng.choice(long_enough, 2, replace=False)
        image, state = sample(a), sample(b)
        swapped = image | {"observation.state": state["observation.state"]}
        act_a, act_b = image["action"][0, :, LEFT_ARM].numpy(), state["action"][0, :, LEFT_ARM].numpy()
        pred, plain = predict(swapped).numpy()[0, :, LEFT_ARM], predict(image).numpy()[0, :, LEFT_ARM]
        rows.append(
            [np.abs(pred - act_a).mean(), np.abs(pred - act_b).mean(), np.abs(plain - act_a).mean()]
            + [np.abs(act_a - act_b).mean()]
        )
    return np.array(rows)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("checkpoints", nargs="+", type=Path, help="pretrained_model folders")
    p.add_argument("--repo-id", required=True)
    p.add_argument("--root", type=Path, required=True, help="the dataset the checkpoints were trained on")
    p.add_argument("--frames", default="40,50,72", help="frame indices to probe")
    p.add_argument("--pairs", type=int, default=20)
    p.add_argument("--episodes", default="0-39", help="training episodes to draw pairs from")
    args = p.parse_args()
    for ckpt in args.checkpoints:
        scenes = training_scenes.TrainingScenes(ckpt, args.repo_id, args.root)
        print(ckpt)
        for frame in int_ranges(args.frames):
            r = swap_errors(scenes, frame, args.pairs, int_ranges(args.episodes))
            print(
                f"  frame {frame:3d}: swapped vs image's {r[:, 0].mean():.3f}, vs state's {r[:, 1].mean():.3f} "
                f"(closer to the state's in {(r[:, 1] < r[:, 0]).mean():.0%}); unswapped vs its own "
                f"{r[:, 2].mean():.3f}; the two recorded chunks {r[:, 3].mean():.3f} apart"
            )


if __name__ == "__main__":
    os.environ.setdefault("MUJOCO_GL", "egl")
    main()
