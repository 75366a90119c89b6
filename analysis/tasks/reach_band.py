"""Measure the arms' reachable band with a horizontal side grasp, on the lower fan (6 cm over its
0.74 m top) or on the two-level workspace's upper band (6 cm over its 1.09 m top, the approach the
upper placements use: the gripper enters horizontally, radially, below the slab's edge height).

For each arm and workspace angle, with the torso turned past the target as the expert turns it, it
reports the distances from the robot base at which IK reaches the pose (standing pose: the torso
only yaws, as in every task), and with ``--plot`` draws both arms' reachable points over the level.

    python analysis/tasks/reach_band.py                                      # lower fan
    python analysis/tasks/reach_band.py --level upper --plot docs/upper_reach.png
"""

from __future__ import annotations

import argparse

import lerobot_activearena  # noqa: F401  (first: pins numpy's BLAS kernels before numpy loads)

# isort: split
import numpy as np


def side_grasp_frames(obj_center: np.ndarray, standoff: float) -> tuple[np.ndarray, np.ndarray]:
    """TCP position ``standoff`` m short of the object along the robot-to-object ray, and the
    gripper rotation (approach horizontal and radial, fingers closing horizontally)."""
    from lerobot_activearena.expert.ik import grasp_rotation

    radial = np.array([obj_center[0], obj_center[1], 0.0])
    radial /= np.linalg.norm(radial)
    closing = np.array([-radial[1], radial[0], 0.0])
    return obj_center - standoff * radial, grasp_rotation(radial, closing)


def reachable(ik, side: str, angle: float, distances, z: float, offset: float) -> list[float]:
    from lerobot_activearena.expert.ik import IKError
    from lerobot_activearena.sim import embodiment

    torso = np.clip(np.radians(angle + offset - 90.0), *embodiment.TORSO_YAW_RANGE)
    ok = []
    for d in distances:
        a = np.radians(angle)
        pos, rot = side_grasp_frames(np.array([d * np.cos(a), d * np.sin(a), z]), 0.0)
        try:
            ik.solve(side, embodiment.HOME_ARM[side], torso, pos, rot, max_iters=400)
            ok.append(float(d))
        except IKError:
            pass
    return ok


def main() -> None:
    from lerobot_activearena.expert.ik import ArmIK
    from lerobot_activearena.sim.workspace import TABLE_TOP, two_level_workspace

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--level", choices=["lower", "upper"], default="lower")
    p.add_argument("--plot", default=None, help="save a plot of the reachable points (PNG)")
    args = p.parse_args()
    upper = two_level_workspace().level(1)
    z = (upper.top_z if args.level == "upper" else TABLE_TOP) + 0.06
    distances = np.round(np.arange(0.30, 0.851, 0.025), 3)
    angles = list(range(30, 151, 10))
    ik = ArmIK()
    print(
        f"side grasp at z = {z:.2f} m (6 cm over the {args.level} top); torso turned 20 deg past the target"
    )
    if args.level == "upper":
        print(f"upper band: r {upper.inner_radius:.2f}-{upper.outer_radius:.2f} m")
    points = {}
    for side, offset in (("left", -20.0), ("right", 20.0)):  # left arm: torso turned right of target
        print(f"{side} arm: angle(deg) -> reachable distances (m)")
        for angle in angles:
            ok = reachable(ik, side, angle, distances, z, offset)
            points[(side, angle)] = ok
            band = f"{min(ok):.3f}-{max(ok):.3f}" if ok else "none"
            print(f"  {angle:4d}: {band}  ({len(ok)}/{len(distances)} grid points)")
    both = [max(min(points["left", a] or [9]), min(points["right", a] or [9])) for a in angles]
    reach = [min(max(points["left", a] or [0]), max(points["right", a] or [0])) for a in angles]
    print(
        f"both arms, every angle {angles[0]}-{angles[-1]} deg: r {max(both):.3f}-{min(reach):.3f} m"
        + (
            f" (upper band {upper.inner_radius:.2f}-{upper.outer_radius:.2f})"
            if args.level == "upper"
            else ""
        )
    )
    if args.plot:
        plot(points, angles, args, upper, z)


def plot(points, angles, args, upper, z) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.2))
    th = np.radians(np.linspace(0, 180, 181))
    if args.level == "upper":
        for r in (upper.inner_radius, upper.outer_radius):
            ax.plot(r * np.cos(th), r * np.sin(th), "k-", lw=1)
        ax.plot([], [], "k-", lw=1, label=f"upper band {upper.inner_radius:.2f}-{upper.outer_radius:.2f} m")
    for side, colour, dx in (("left", "tab:blue", -0.004), ("right", "tab:orange", 0.004)):
        xs, ys = [], []
        for a in angles:
            for d in points[side, a]:
                xs.append(d * np.cos(np.radians(a)) + dx)
                ys.append(d * np.sin(np.radians(a)))
        ax.scatter(xs, ys, s=10, c=colour, label=f"{side} arm reaches")
    ax.scatter([0], [0], marker="^", c="k", s=40, label="robot base")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m, ahead)")
    ax.set_title(f"Side-grasp reach, z = {z:.2f} m ({args.level} top + 6 cm)")
    ax.legend(loc="upper left", fontsize="small", bbox_to_anchor=(1.0, 1.0))
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
