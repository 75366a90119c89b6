"""Measure the arms' reachable band on the lower fan (side grasp at 6 cm over the tabletop).

For each arm and workspace angle, with the torso turned to face that angle (as the expert does),
reports the distances from the robot base at which IK reaches a horizontal side-grasp pose.

    python benchmarks/reach_band.py
"""

from __future__ import annotations

import numpy as np


def side_grasp_frames(obj_center: np.ndarray, standoff: float) -> tuple[np.ndarray, np.ndarray]:
    """TCP position ``standoff`` m short of the object along the robot-to-object ray, and the
    gripper rotation (approach horizontal and radial, fingers closing horizontally)."""
    from lerobot_activearena.expert.ik import grasp_rotation

    radial = np.array([obj_center[0], obj_center[1], 0.0])
    radial /= np.linalg.norm(radial)
    closing = np.array([-radial[1], radial[0], 0.0])
    return obj_center - standoff * radial, grasp_rotation(radial, closing)


def main() -> None:
    from lerobot_activearena.expert.ik import ArmIK, IKError
    from lerobot_activearena.sim import embodiment

    ik = ArmIK()
    distances = np.round(np.arange(0.30, 0.81, 0.05), 2)
    print(
        "side grasp at z = 0.80 m (6 cm over the 0.74 m table); torso yaw faces the target angle +/- 20 deg"
    )
    for side, offset in (("left", -20.0), ("right", 20.0)):  # left arm: torso turned right of target
        print(f"{side} arm: angle(deg) -> reachable distances (m)")
        for angle in (30, 60, 90, 120, 150):
            torso = np.clip(np.radians(angle + offset - 90.0), -1.2, 1.2)
            ok = []
            for d in distances:
                a = np.radians(angle)
                center = np.array([d * np.cos(a), d * np.sin(a), 0.80])
                pos, rot = side_grasp_frames(center, 0.0)
                try:
                    ik.solve(side, embodiment.HOME_ARM[side], torso, pos, rot, max_iters=400)
                    ok.append(d)
                except IKError:
                    pass
            band = f"{min(ok):.2f}-{max(ok):.2f}" if ok else "none"
            print(f"  {angle:4d}: {band}  ({len(ok)}/{len(distances)} grid points)")


if __name__ == "__main__":
    main()
