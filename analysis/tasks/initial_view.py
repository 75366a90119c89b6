"""The head camera's home view over the lower fan, and the arms' top-down reach band.

Prints, per distance from the robot base, the band of workspace angles (deg; 90 = straight ahead)
whose tabletop points project inside the 512x384 head image at home (torso yaw 0, head pitch 1.0),
the hidden angles on each side, and, per arm, the band of distances a top-down press reaches at
each angle with the torso turned as the expert turns it. The view should be symmetric about 90 deg.

    python analysis/tasks/initial_view.py
"""

from __future__ import annotations

import argparse

import lerobot_activearena  # noqa: F401  (first: pins numpy's BLAS kernels before numpy loads)

# isort: split
import numpy as np


def visible_band(radius: float, angles: np.ndarray, height: float) -> tuple[float, float] | None:
    """Smallest and largest angle whose tabletop point at ``height`` projects into the home image."""
    from lerobot_activearena.sim.workspace import TABLE_TOP
    from lerobot_activearena.tasks.draft import in_home_view

    a = np.radians(angles)
    inside = np.array(
        [
            in_home_view((radius * np.cos(x), radius * np.sin(x)), 0.0, heights=(height - TABLE_TOP,))
            for x in a
        ]
    )
    if not inside.any():
        return None
    return float(angles[inside].min()), float(angles[inside].max())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--height", type=float, default=0.76, help="height of the sampled points (m)")
    args = parser.parse_args()
    from lerobot_activearena.expert.kinematics import top_down_reachable

    angles = np.arange(20.0, 160.01, 0.5)
    print(f"home view (torso yaw 0, head pitch 1.0) at z = {args.height} m; fan placements span 20-160 deg")
    print(f"{'r (m)':>6} {'visible (deg)':>16} {'hidden right':>14} {'hidden left':>14} {'asymmetry':>10}")
    for r in np.arange(0.30, 1.001, 0.05):
        band = visible_band(float(r), angles, args.height)
        if band is None:
            print(f"{r:6.2f} {'none':>16}")
            continue
        lo, hi = band
        right = f"20.0-{lo:.1f}" if lo > 20 else "-"
        left = f"{hi:.1f}-160.0" if hi < 160 else "-"
        print(f"{r:6.2f} {f'{lo:.1f}-{hi:.1f}':>16} {right:>14} {left:>14} {(lo - 20) - (160 - hi):10.1f}")
    print("\ntop-down reach (press / grasp height 0 and +10 cm) with the expert's torso turn:")
    radii = np.round(np.arange(0.30, 0.601, 0.02), 2)
    for side in ("left", "right"):
        print(f"{side} arm: angle (deg) -> reachable distances (m)")
        for angle in (25, 40, 55, 70, 90, 110, 125, 140, 155):
            ok = [
                r
                for r in radii
                if top_down_reachable(
                    np.array([r * np.cos(np.radians(angle)), r * np.sin(np.radians(angle)), 0.78]), side
                )
            ]
            print(f"  {angle:4d}: {f'{min(ok):.2f}-{max(ok):.2f}' if ok else 'none'}")


if __name__ == "__main__":
    main()
