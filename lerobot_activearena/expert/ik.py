"""Arm inverse kinematics with mink on a robot-only model (one arm solved, everything else frozen)."""

from __future__ import annotations

import math

import mink
import mujoco
import numpy as np

from ..sim import embodiment


class IKError(RuntimeError):
    pass


def grasp_rotation(approach: np.ndarray, closing: np.ndarray) -> np.ndarray:
    """Gripper frame for an approach direction (gripper +z) and finger-closing axis (gripper +x)."""
    z = np.asarray(approach, float)
    z = z / np.linalg.norm(z)
    x = np.asarray(closing, float)
    x = x - z * (x @ z)
    x = x / np.linalg.norm(x)
    return np.stack([x, np.cross(z, x), z], axis=1)


class ArmIK:
    """Solves TCP pose targets for one arm at a time, holding the torso and the other arm fixed."""

    def __init__(self):
        spec = mujoco.MjSpec()
        embodiment.add_robot(spec)
        self.model = spec.compile()
        self.configuration = mink.Configuration(self.model)
        self._qadr = {
            s: np.array([self.model.joint(j).qposadr[0] for j in embodiment.ARM_JOINTS[s]])
            for s in ("left", "right")
        }
        self._dof = {
            s: [int(self.model.joint(j).dofadr[0]) for j in embodiment.ARM_JOINTS[s]]
            for s in ("left", "right")
        }
        self._other_qadr = {
            "torso": self.model.joint(embodiment.TORSO_YAW_JOINT).qposadr[0],
            "head": self.model.joint(embodiment.HEAD_PITCH_JOINT).qposadr[0],
        }
        self.limits = [mink.ConfigurationLimit(self.model)]
        self._freeze = {
            s: mink.DofFreezingTask(self.model, [d for d in range(self.model.nv) if d not in self._dof[s]])
            for s in ("left", "right")
        }
        self._task = {
            s: mink.FrameTask(
                embodiment.TCP_SITES[s], "site", position_cost=1.0, orientation_cost=0.5, lm_damping=1e-3
            )
            for s in ("left", "right")
        }
        self._posture = mink.PostureTask(self.model, cost=1e-3)

    def solve(
        self,
        side: str,
        arm_q: np.ndarray,
        torso_yaw: float,
        target_pos,
        target_rot,
        max_iters: int = 300,
        pos_tol: float = 1e-3,
        rot_tol: float = 1e-2,
    ) -> np.ndarray:
        """Return 7 joint angles that put ``side``'s TCP at (target_pos, target_rot)."""
        q = self.model.qpos0.copy()
        q[self._qadr[side]] = arm_q
        q[self._other_qadr["torso"]] = torso_yaw
        self.configuration.update(q)
        task = self._task[side]
        target = mink.SE3.from_rotation_and_translation(
            mink.SO3.from_matrix(np.asarray(target_rot)), np.asarray(target_pos)
        )
        task.set_target(target)
        self._posture.set_target(q)
        dt = 0.05
        for _ in range(max_iters):
            vel = mink.solve_ik(
                self.configuration,
                [task, self._posture],
                dt,
                "daqp",
                damping=1e-3,
                limits=self.limits,
                constraints=[self._freeze[side]],
            )
            self.configuration.integrate_inplace(vel, dt)
            err = task.compute_error(self.configuration)
            if np.linalg.norm(err[:3]) < pos_tol and np.linalg.norm(err[3:]) < rot_tol:
                return self.configuration.q[self._qadr[side]].copy()
        raise IKError(
            f"{side} arm IK did not converge to {np.round(target_pos, 3)} (position error "
            f"{np.linalg.norm(err[:3]) * 1000:.1f} mm, rotation error {np.linalg.norm(err[3:]):.3f} rad)"
        )

    def tcp_pose(self, side: str, arm_q: np.ndarray, torso_yaw: float) -> tuple[np.ndarray, np.ndarray]:
        q = self.model.qpos0.copy()
        q[self._qadr[side]] = arm_q
        q[self._other_qadr["torso"]] = torso_yaw
        self.configuration.update(q)
        site = self.configuration.data.site(embodiment.TCP_SITES[side])
        return site.xpos.copy(), site.xmat.reshape(3, 3).copy()

    def shoulder(self, side: str, torso_yaw: float) -> np.ndarray:
        """World position of the ``side`` arm's first joint at torso yaw ``torso_yaw``."""
        q = self.model.qpos0.copy()
        q[self._other_qadr["torso"]] = torso_yaw
        self.configuration.update(q)
        return self.configuration.data.body(f"{embodiment.PREFIX}arm_{side}_link_1").xpos.copy()


def rot_z(angle: float) -> np.ndarray:
    """Rotation by ``angle`` rad about the world vertical."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], float)


def interpolate_pose(p0, rot0, p1, rot1, s: float) -> tuple[np.ndarray, np.ndarray]:
    """Straight-line position and geodesic rotation between two poses, at fraction ``s``."""
    r0, r1 = mink.SO3.from_matrix(np.asarray(rot0)), mink.SO3.from_matrix(np.asarray(rot1))
    delta = (r0.inverse() @ r1).log()
    rot = (r0 @ mink.SO3.exp(s * delta)).as_matrix()
    return (1 - s) * np.asarray(p0) + s * np.asarray(p1), rot
