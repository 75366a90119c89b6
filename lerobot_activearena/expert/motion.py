"""Time profiles: turn a goal into a sequence of 15 Hz 18-D actions, or wait (``hold``, ``await_trailing``, ``halt``)."""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import TYPE_CHECKING

import numpy as np

from ..sim.action import CONTROL_HZ, LEFT_ARM, LEFT_GRIPPER, RIGHT_ARM, RIGHT_GRIPPER

if TYPE_CHECKING:
    from .context import ExpertContext

CONTROL_DT = 1.0 / CONTROL_HZ
Actions = Iterator[np.ndarray]  # what the expert's moves yield: one 18-D action per control step


def interpolate_joints(
    start: np.ndarray, goal: np.ndarray, max_vel: float = 1.0, min_steps: int = 2
) -> list[np.ndarray]:
    """Linear joint-space path at <= ``max_vel`` rad/s (the paper's move_joint fallback), with a
    smooth (cosine) time scaling; returns the actions after ``start``, ending exactly at ``goal``."""
    start, goal = np.asarray(start, float), np.asarray(goal, float)
    span = np.max(np.abs(goal - start)) if goal.size else 0.0
    # Cosine profile peaks at pi/2 x mean velocity: stretch so the peak respects max_vel.
    n = max(min_steps, int(np.ceil(span * np.pi / 2 / (max_vel * CONTROL_DT))))
    s = 0.5 - 0.5 * np.cos(np.pi * np.arange(1, n + 1) / n)
    return [start + si * (goal - start) for si in s]


def trapezoid(distance: float, vmax: float, amax: float, dt: float = CONTROL_DT) -> np.ndarray:
    """Fractions s_k in (0, 1] of a trapezoidal (or triangular) velocity profile covering
    ``distance`` with peak speed <= vmax and acceleration <= amax, sampled every ``dt``."""
    d = abs(distance)
    if d < 1e-9:
        return np.array([1.0])
    t_acc = vmax / amax
    if amax * t_acc**2 >= d:  # triangular: never reaches vmax
        t_acc = math.sqrt(d / amax)
        vpk = amax * t_acc
        t_total = 2 * t_acc
    else:
        vpk = vmax
        t_total = 2 * t_acc + (d - amax * t_acc**2) / vmax
    n = max(1, int(math.ceil(t_total / dt)))
    t = np.linspace(t_total / n, t_total, n)
    pos = np.where(
        t < t_acc,
        0.5 * amax * t**2,
        np.where(
            t <= t_total - t_acc,
            0.5 * amax * t_acc**2 + vpk * (t - t_acc),
            d - 0.5 * amax * (t_total - t) ** 2,
        ),
    )
    return np.clip(pos / d, 0.0, 1.0)


def with_arm(
    base: np.ndarray, side: str, arm_q: np.ndarray | None = None, gripper: float | None = None
) -> np.ndarray:
    a = np.asarray(base, float).copy()
    sl, g = (LEFT_ARM, LEFT_GRIPPER) if side == "left" else (RIGHT_ARM, RIGHT_GRIPPER)
    if arm_q is not None:
        a[sl] = arm_q
    if gripper is not None:
        a[g] = gripper
    return a


def arm_of(action: np.ndarray, side: str) -> np.ndarray:
    return np.asarray(action)[LEFT_ARM if side == "left" else RIGHT_ARM].copy()


def gripper_index(side: str) -> int:
    return LEFT_GRIPPER if side == "left" else RIGHT_GRIPPER


def hold(ctx: ExpertContext, steps: int) -> Actions:
    for _ in range(steps):
        yield ctx.emit()


def await_trailing(ctx: ExpertContext, side: str | None = None) -> Actions:
    """Hold until the ``side`` arm's trailing motion (None: every arm's) has ended."""
    while (side in ctx.trailing) if side is not None else ctx.trailing:
        yield ctx.emit()


def halt(ctx: ExpertContext, side: str) -> None:
    """Stop the ``side`` arm's trailing motion where it is (it is needed again: no need to go home)."""
    ctx.trailing.pop(side, None)
