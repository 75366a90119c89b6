"""Simulator throughput on the reference scene (robot + fan table + 25 objects), on one core.

Prints the physics rate through ``sim.step`` (as a ratio to bare ``mj_step``), head RGB render rate, visibility rate and annotated control steps per second
(physics for 1/15 s + 512x384 RGB + visibility of every object). Target: >= 40 annotated steps/s.

    MUJOCO_GL=egl python benchmarks/sim_throughput.py [--steps 150] [--cores 1] [--shadows]

``--shadows``: the key light casts shadows (off in every scene the benchmark ships; docs/sim.md).
"""

from __future__ import annotations

import argparse
import os

import lerobot_activearena  # noqa: F401  (first: pins numpy's BLAS kernels before numpy loads)


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--steps", type=int, default=150, help="control steps per measurement")
    p.add_argument("--cores", type=int, default=1, help="CPU cores to pin to (llvmpipe threads follow)")
    p.add_argument("--objects", type=int, default=25)
    p.add_argument("--no-sleep", action="store_true", help="keep every object awake (MuJoCo sleeping off)")
    p.add_argument("--shadows", action="store_true", help="the key light casts shadows")
    p.add_argument("--shadow-size", type=int, default=None, help="shadow map size (default: the scene's)")
    args = p.parse_args()
    os.sched_setaffinity(0, set(range(args.cores)))
    os.environ.setdefault("LP_NUM_THREADS", "0" if args.cores == 1 else str(args.cores))

    import time

    import mujoco
    import numpy as np

    from lerobot_activearena.sim.scene import reference_scene
    from lerobot_activearena.sim.simulator import ActiveArenaSim

    builder = reference_scene(0, n_objects=args.objects)
    if args.no_sleep:
        builder.spec.option.enableflags &= ~int(mujoco.mjtEnableBit.mjENBL_SLEEP)
    if args.shadows:
        builder.spec.light("key_light").castshadow = True
    if args.shadow_size:
        builder.spec.visual.quality.shadowsize = args.shadow_size
    model, info = builder.compile()
    sim = ActiveArenaSim(model, info)
    home = sim.home_action()

    def actions(n):
        for i in range(n):
            a = home.copy()
            a[16] = 1.0 * np.sin(2 * np.pi * i / 90)  # torso sweeps the view over the fan
            a[17] = 1.0 - 0.3 * (0.5 + 0.5 * np.sin(2 * np.pi * i / 60))
            yield a

    for a in actions(10):  # settle and warm up the renderer
        sim.step(a)
        sim.render_head()

    def rate(fn, n):
        t = time.perf_counter()
        for _ in range(n):
            fn()
        return n / (time.perf_counter() - t)

    t = time.perf_counter()
    for a in actions(args.steps):
        sim.step(a)
    phys = args.steps * sim.substeps / (time.perf_counter() - t)
    t = time.perf_counter()
    for _ in range(args.steps * sim.substeps):  # MuJoCo alone: the controls held, no controller
        mujoco.mj_step(model, sim.data)
    raw = args.steps * sim.substeps / (time.perf_counter() - t)
    render = rate(sim.render_head, args.steps)
    vis = rate(sim.visibility, args.steps)

    t = time.perf_counter()
    for a in actions(args.steps):
        sim.step(a)
        sim.render_head()
        sim.visibility()
        sim.head_camera()
        sim.end_effector_poses()
    annotated = args.steps / (time.perf_counter() - t)
    print(
        f"scene: robot + fan table + {len(info.objects)} objects, nbody={model.nbody}, ngeom={model.ngeom}; "
        f"cores={args.cores}, MUJOCO_GL={os.environ.get('MUJOCO_GL')}, sleeping={'off' if args.no_sleep else 'on'}, "
        f"shadows={'on' if args.shadows else 'off'}"
    )
    print(
        f"mj_step:                     {phys:8.0f} steps/s  (timestep {model.opt.timestep * 1000:.3f} ms, "
        f"{sim.substeps} per control step; {phys / raw:.2f}x bare mj_step's {raw:.0f}/s: the "
        "controller's share)"
    )
    print(f"head RGB render 512x384:     {render:8.1f} frames/s")
    print(f"visibility ({len(info.objects)} objects):      {vis:8.1f} evals/s")
    print(f"annotated control steps:     {annotated:8.1f} steps/s  (target >= 40)")


if __name__ == "__main__":
    main()
