"""What a task's scenes cost to build and to draw, by split: milliseconds per reset (sampling, MjSpec
build, compile, first observation) and per head-camera frame (512x384) while the robot holds still.
The OOD split's denser clutter is where dressed distractors cost most.

    MUJOCO_GL=egl python benchmarks/scene_cost.py --task click_bell_rotate_view --seeds 6 --frames 30

Pinned to one core. Compare looks by running two trees in turn on the same machine (figures from a
shared machine are only good as ratios): ``PYTHONPATH=<other checkout> python benchmarks/scene_cost.py``.
"""

from __future__ import annotations

import argparse
import os

import lerobot_activearena  # noqa: F401  (first: pins numpy's BLAS kernels before numpy loads)


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--task", default="click_bell_rotate_view")
    p.add_argument("--splits", default="id,ood")
    p.add_argument("--seeds", type=int, default=6, help="manifest episodes per split")
    p.add_argument("--frames", type=int, default=30, help="head renders per episode")
    args = p.parse_args()
    os.sched_setaffinity(0, {0})
    os.environ.setdefault("LP_NUM_THREADS", "0")

    import time

    import numpy as np

    from lerobot_activearena.envs.gym_env import ActiveArenaEnv

    print(f"package: {os.path.dirname(lerobot_activearena.__file__)}")
    for split in args.splits.split(","):
        env = ActiveArenaEnv(task=args.task, split=split)
        resets, frames, drawn = [], [], []
        for k in range(args.seeds):
            t0 = time.perf_counter()
            env.reset(seed=env.seed_base + k)
            resets.append(time.perf_counter() - t0)
            m = env.sim.model
            drawn.append(
                int(sum(m.mesh_facenum[m.geom_dataid[g]] for g in range(m.ngeom) if m.geom_type[g] == 7))
            )
            t0 = time.perf_counter()
            for _ in range(args.frames):
                env.sim.render_head()
            frames.append((time.perf_counter() - t0) / args.frames)
        env.close()
        print(
            f"{args.task} {split}: reset {1e3 * np.median(resets):.0f} ms, head frame "
            f"{1e3 * np.median(frames):.1f} ms (median of {args.seeds} scenes), "
            f"mesh triangles per scene {int(np.median(drawn))}"
        )


if __name__ == "__main__":
    main()
