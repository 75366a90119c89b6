"""One shared robot-only kinematics model per process: arm IK and head-camera gaze."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..sim import embodiment
from .gaze import Gaze, heading_deg
from .ik import ArmIK, IKError, grasp_rotation

ARM_TORSO_OFFSET_DEG = 15.0  # torso turns this far past the object so it sits in front of the arm


@lru_cache(maxsize=1)
def shared_kinematics() -> tuple[ArmIK, Gaze]:
    ik = ArmIK()
    return ik, Gaze(ik.model)


def torso_yaw_for_arm(point, side: str) -> float:
    offset = -ARM_TORSO_OFFSET_DEG if side == "left" else ARM_TORSO_OFFSET_DEG
    return float(np.clip(math.radians(heading_deg(point) - 90.0 + offset), *embodiment.TORSO_YAW_RANGE))


def top_down_reachable(point, side: str, heights=(0.0, 0.10)) -> bool:
    """Whether ``side``'s gripper reaches straight down over ``point`` (at each of ``heights`` above
    it) with the torso turned as the expert turns it, for either finger orientation."""

    ik, _ = shared_kinematics()
    yaw = torso_yaw_for_arm(point, side)
    radial = np.array([point[0], point[1], 0.0]) / np.linalg.norm(point[:2])
    closing = np.array([-radial[1], radial[0], 0.0])
    for sign in (1.0, -1.0):
        rot = grasp_rotation([0, 0, -1], sign * closing)
        try:
            for h in heights:
                ik.solve(
                    side,
                    embodiment.HOME_ARM[side],
                    yaw,
                    np.asarray(point, float) + [0, 0, h],
                    rot,
                    max_iters=400,
                )
            return True
        except IKError:
            continue
    return False


def side_reachable(point, side: str, height: float = 0.06) -> bool:
    """Whether ``side``'s gripper reaches ``point`` (raised ``height`` m) with the horizontal, radial
    side grasp (fingers closing horizontally) that upper-band placements use, the torso turned as
    the expert turns it."""
    ik, _ = shared_kinematics()
    p = np.asarray(point, float) + [0, 0, height]
    radial = np.array([p[0], p[1], 0.0]) / np.linalg.norm(p[:2])
    rot = grasp_rotation(radial, np.array([-radial[1], radial[0], 0.0]))
    try:
        ik.solve(side, embodiment.HOME_ARM[side], torso_yaw_for_arm(p, side), p, rot, max_iters=400)
    except IKError:
        return False
    return True
