"""Where to point the head camera: torso yaw for azimuth, head pitch for elevation (paper's
look-at primitives), solved on the robot's own kinematics."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from ..sim import embodiment


def heading_deg(point) -> float:
    """Workspace angle of a world point around the robot base (90 deg = straight ahead)."""
    return math.degrees(math.atan2(point[1], point[0]))


class Gaze:
    def __init__(self, model: mujoco.MjModel):
        self.model = model
        self.data = mujoco.MjData(model)
        self.cam = model.camera(embodiment.HEAD_CAMERA).id
        self.q_yaw = model.joint(embodiment.TORSO_YAW_JOINT).qposadr[0]
        self.q_pitch = model.joint(embodiment.HEAD_PITCH_JOINT).qposadr[0]

    def _angles(self, point, yaw: float, pitch: float) -> np.ndarray:
        """(horizontal, vertical) angle of ``point`` off the optical axis, radians."""
        self.data.qpos[self.q_yaw], self.data.qpos[self.q_pitch] = yaw, pitch
        mujoco.mj_kinematics(self.model, self.data)
        mujoco.mj_camlight(self.model, self.data)
        rot = self.data.cam_xmat[self.cam].reshape(3, 3)
        v = rot.T @ (np.asarray(point, float) - self.data.cam_xpos[self.cam])  # camera looks along -z
        return np.array([math.atan2(v[0], -v[2]), math.atan2(v[1], -v[2])])

    def aim(
        self, point, yaw: float, pitch: float, fix_yaw: bool = False, iters: int = 8
    ) -> tuple[float, float]:
        """Torso yaw and head pitch that centre ``point`` in the image (Newton steps with a
        finite-difference Jacobian); with ``fix_yaw`` only the pitch moves. Clipped to the limits."""
        x = np.array([yaw, pitch], float)
        eps = 1e-4
        for _ in range(iters):
            e = self._angles(point, *x)
            jac = np.stack(
                [
                    (self._angles(point, x[0] + eps, x[1]) - e) / eps,
                    (self._angles(point, x[0], x[1] + eps) - e) / eps,
                ],
                axis=1,
            )
            dx = np.array([0.0, -e[1] / jac[1, 1]]) if fix_yaw else -np.linalg.solve(jac, e)
            x = x + np.clip(dx, -0.5, 0.5)
            x[0] = np.clip(x[0], *embodiment.TORSO_YAW_RANGE)
            x[1] = np.clip(x[1], *embodiment.HEAD_PITCH_RANGE)
            if np.max(np.abs(dx)) < 1e-4:
                break
        return float(x[0]), float(x[1])
