"""Joint-target controller between 15 Hz actions and the physics substeps.

Arm targets are linearly interpolated over the control period; torso yaw and head pitch follow a
velocity/acceleration-limited (trapezoidal) profile with the paper's limits; grippers are set
directly (their actuators are force-limited).
"""

from __future__ import annotations

import math

import numpy as np

from .action import ACTION_DIM, HEAD_PITCH, LEFT_ARM, RIGHT_ARM, TORSO_YAW
from .embodiment import HEAD_LIMITS, TORSO_LIMITS


class RateLimitedAxis:
    """A 1-D reference that moves toward a goal with bounded velocity and acceleration."""

    def __init__(self, vmax: float, amax: float, q: float):
        self.vmax, self.amax = vmax, amax
        self.q, self.v = float(q), 0.0

    def reset(self, q: float) -> None:
        self.q, self.v = float(q), 0.0

    def step(self, goal: float, dt: float) -> float:
        e = float(goal - self.q)
        # Fastest velocity that can still stop at the goal (scalar math: numpy's per-call cost
        # dominated the substep; the arithmetic is the same).
        v_des = ((e > 0) - (e < 0)) * min(self.vmax, math.sqrt(2 * self.amax * abs(e)))
        dv = min(max(v_des - self.v, -self.amax * dt), self.amax * dt)
        self.v += dv
        q_next = self.q + self.v * dt
        if (goal - q_next) * e <= 0:  # would pass the goal: land on it
            q_next, self.v = goal, 0.0
        self.q = q_next
        return self.q


class JointTargetController:
    """Turns one 18-D action into per-substep actuator targets (16 joints + 2 grippers)."""

    def __init__(self, substeps: int, dt: float):
        self.substeps, self.dt = substeps, dt
        self.prev = np.zeros(ACTION_DIM)
        self.torso = RateLimitedAxis(*TORSO_LIMITS, 0.0)
        self.head = RateLimitedAxis(*HEAD_LIMITS, 0.0)

    def reset(self, state18: np.ndarray) -> None:
        self.prev = np.asarray(state18, float).copy()
        self.torso.reset(state18[TORSO_YAW])
        self.head.reset(state18[HEAD_PITCH])

    def substep_targets(self, target: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The 18-D reference of each physics substep of one control step, (substeps, 18), and the
        torso-yaw / head-pitch reference velocities (rad/s) at each, (substeps, 2): the velocity
        drives' targets."""
        target = np.asarray(target, float)
        start = self.prev
        refs = np.tile(target, (self.substeps, 1))
        alpha = (np.arange(1, self.substeps + 1) / self.substeps)[:, None]
        for sl in (LEFT_ARM, RIGHT_ARM):
            refs[:, sl] = start[sl] + alpha * (target[sl] - start[sl])
        velocity = np.empty((self.substeps, 2))
        for k in range(self.substeps):
            refs[k, TORSO_YAW] = self.torso.step(target[TORSO_YAW], self.dt)
            refs[k, HEAD_PITCH] = self.head.step(target[HEAD_PITCH], self.dt)
            velocity[k] = self.torso.v, self.head.v
        self.prev = target.copy()
        return refs, velocity
