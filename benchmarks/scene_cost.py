"""What a task's scenes cost to build and to draw, by split: milliseconds per reset (sampling, MjSpec
build, compile, first observation) and per head-camera frame (512x384) while the robot holds still,
the mesh triangles drawn, and how many scenes hold a dressed distractor (``--frames 0`` for that
count alone). The OOD split's denser clutter is where dressed distractors cost most.

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

    import mujoco
    import numpy as np

    from lerobot_activearena.envs.gym_env import ActiveArenaEnv
    from lerobot_activearena.sim.look.dress import DRESS_GROUP

    print(f"package: {os.path.dirname(lerobot_activearena.__file__)}")
    for split in args.splits.split(","):
        env = ActiveArenaEnv(task=args.task, split=split)
        resets, frames, drawn, dressed_clutter = [], [], [], 0
        for k in range(args.seeds):
            t0 = time.perf_counter()
            env.reset(seed=env.seed_base + k)
            resets.append(time.perf_counter() - t0)
            m = env.sim.model
            meshes = [g for g in range(m.ngeom) if m.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH]
            drawn.append(int(sum(m.mesh_facenum[m.geom_dataid[g]] for g in meshes)))
            dressed_clutter += any(
                m.geom_group[g] == DRESS_GROUP and m.body(m.geom_bodyid[g]).name.startswith("clutter_")
                for g in meshes
            )
            t0 = time.perf_counter()
            for _ in range(args.frames):
                env.sim.render_head()
            frames.append((time.perf_counter() - t0) / max(args.frames, 1))
        env.close()
        print(
            f"{args.task} {split}: reset {1e3 * np.median(resets):.0f} ms, head frame "
            f"{f'{1e3 * np.median(frames):.1f} ms' if args.frames else '-'} (median of {args.seeds} scenes), "
            f"mesh triangles per scene {int(np.median(drawn))}, scenes with a dressed distractor "
            f"{dressed_clutter}/{args.seeds}"
        )


if __name__ == "__main__":
    main()
