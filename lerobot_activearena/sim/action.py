"""The 18-D action/state layout and its validation.

``[left arm 7, left gripper, right arm 7, right gripper, torso yaw, head pitch]``: absolute joint
targets; grippers are normalised, 0 = closed and 1 = open.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

CONTROL_HZ = 15  # actions are commanded (and frames recorded) at the paper's 15 Hz
ACTION_DIM = 18
LEFT_ARM = slice(0, 7)
LEFT_GRIPPER = 7
RIGHT_ARM = slice(8, 15)
RIGHT_GRIPPER = 15
TORSO_YAW = 16
HEAD_PITCH = 17
GRIPPER_INDICES = (LEFT_GRIPPER, RIGHT_GRIPPER)

ACTION_NAMES = (
    [f"left_arm_joint_{i}" for i in range(1, 8)]
    + ["left_gripper"]
    + [f"right_arm_joint_{i}" for i in range(1, 8)]
    + ["right_gripper", "torso_yaw", "head_pitch"]
)


@dataclass
class ClipReport:
    """Which action entries were outside their limits, and by how much (after clipping)."""

    indices: np.ndarray
    requested: np.ndarray
    applied: np.ndarray

    @property
    def any(self) -> bool:
        return self.indices.size > 0

    def as_dict(self) -> dict[str, tuple[float, float]]:
        return {
            ACTION_NAMES[i]: (float(r), float(a))
            for i, r, a in zip(self.indices, self.requested, self.applied, strict=True)
        }


def validate_action(action) -> np.ndarray:
    """Raise a clear error for a wrong shape, dtype or non-finite action; return float64 copy."""
    arr = np.asarray(action)
    if arr.shape != (ACTION_DIM,):
        raise ValueError(
            f"action must have shape ({ACTION_DIM},) laid out as {ACTION_NAMES[0]}..{ACTION_NAMES[-1]}; "
            f"got shape {arr.shape}. For a batch, step each environment with its own row."
        )
    if not (np.issubdtype(arr.dtype, np.floating) or np.issubdtype(arr.dtype, np.integer)):
        raise TypeError(f"action must be a real-valued numeric array, got dtype {arr.dtype}")
    arr = arr.astype(np.float64)
    bad = ~np.isfinite(arr)
    if bad.any():
        names = [ACTION_NAMES[i] for i in np.flatnonzero(bad)]
        raise ValueError(f"action has non-finite values (NaN/inf) at {names}; check the policy output")
    return arr


FLOAT32_SLACK = 1e-6  # a float32 round trip of a target exactly at a limit lands this far past it


def clip_action(action: np.ndarray, low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, ClipReport]:
    """Clip to the limits; report the entries that were beyond them by more than float32 rounding."""
    clipped = np.clip(action, low, high)
    idx = np.flatnonzero(np.abs(clipped - action) > FLOAT32_SLACK)
    return clipped, ClipReport(idx, action[idx], clipped[idx])
