"""Joint-space motion: turn a goal into a sequence of 15 Hz 18-D actions."""

from __future__ import annotations

import numpy as np

from ..sim import action as A

CONTROL_DT = 1.0 / 15


def interpolate_joints(start: np.ndarray, goal: np.ndarray, max_vel: float = 1.0, min_steps: int = 2) -> list[np.ndarray]:
    """Linear joint-space path at <= ``max_vel`` rad/s (the paper's move_joint fallback), with a
    smooth (cosine) time scaling; returns the actions after ``start``, ending exactly at ``goal``."""
    start, goal = np.asarray(start, float), np.asarray(goal, float)
    span = np.max(np.abs(goal - start)) if goal.size else 0.0
    # Cosine profile peaks at pi/2 x mean velocity: stretch so the peak respects max_vel.
    n = max(min_steps, int(np.ceil(span * np.pi / 2 / (max_vel * CONTROL_DT))))
    s = 0.5 - 0.5 * np.cos(np.pi * np.arange(1, n + 1) / n)
    return [start + si * (goal - start) for si in s]


def with_arm(base: np.ndarray, side: str, arm_q: np.ndarray | None = None, gripper: float | None = None) -> np.ndarray:
    a = np.asarray(base, float).copy()
    sl, g = (A.LEFT_ARM, A.LEFT_GRIPPER) if side == "left" else (A.RIGHT_ARM, A.RIGHT_GRIPPER)
    if arm_q is not None:
        a[sl] = arm_q
    if gripper is not None:
        a[g] = gripper
    return a


def arm_of(action: np.ndarray, side: str) -> np.ndarray:
    return np.asarray(action)[A.LEFT_ARM if side == "left" else A.RIGHT_ARM].copy()
