"""The simulator: 18-D joint-target control at 15 Hz, head-camera rendering, camera parameters,
end-effector poses and per-object visibility for a compiled scene."""

from __future__ import annotations

import logging

import mujoco
import numpy as np

from . import embodiment
from .action import (
    ACTION_DIM,
    GRIPPER_INDICES,
    HEAD_PITCH,
    LEFT_ARM,
    LEFT_GRIPPER,
    RIGHT_ARM,
    RIGHT_GRIPPER,
    TORSO_YAW,
    ClipReport,
    clip_action,
    validate_action,
)
from .blas_kernels import use_pinned_kernels
from .camera import cam2world_gl, extrinsic_cv, intrinsics
from .controller import JointTargetController
from .gl_backend import rendering_error
from .head_camera import head_visibility_checker, validate_head_size
from .look.dress import scene_option
from .scene import CONTROL_HZ, HEAD_HEIGHT, HEAD_WIDTH, SUBSTEPS, WRIST_HEIGHT, WRIST_WIDTH, SceneInfo
from .visibility import Visibility

log = logging.getLogger(__name__)


class ActiveArenaSim:
    def __init__(
        self,
        model: mujoco.MjModel,
        info: SceneInfo,
        image_height: int = HEAD_HEIGHT,
        image_width: int = HEAD_WIDTH,
    ):
        """``image_height`` x ``image_width``: the head image's size (3:4; default the paper's
        384 x 512). The head camera renders at that size, and its intrinsics, visibility boxes and
        image points follow it."""
        use_pinned_kernels()  # the same BLAS kernels on every x86-64 CPU (sim/blas_kernels.py)
        self.model, self.info = model, info
        self.image_height, self.image_width = validate_head_size(image_height, image_width)
        glob = model.vis.global_  # the offscreen buffer must hold the largest image rendered
        glob.offheight, glob.offwidth = (
            max(glob.offheight, self.image_height),
            max(glob.offwidth, self.image_width),
        )
        self.data = mujoco.MjData(model)
        self._draw = scene_option()  # dressed looks drawn, the shapes they replace hidden
        self.substeps = SUBSTEPS
        self.control_dt = 1.0 / CONTROL_HZ
        if abs(model.opt.timestep * SUBSTEPS - self.control_dt) > 1e-9:
            raise ValueError("model timestep must be 1/(15*SUBSTEPS) s")
        robot = info.robot
        # Action entries that are joint angles (all but the grippers) and their qpos addresses.
        self._grip_idx = np.array(GRIPPER_INDICES)
        self._joint_idx = np.array([i for i in range(ACTION_DIM) if i not in GRIPPER_INDICES])
        self._joint_qadr = np.array([model.joint(j).qposadr[0] for j in robot.actuated_joints])
        # Gripper joint addresses per side: the active joint first, then its followers with coefficients.
        self._grip_qadr = np.array(
            [model.joint(robot.gripper_joints[s]).qposadr[0] for s in ("left", "right")]
        )
        self._finger_qadr = np.array(
            [
                [
                    model.joint(f"{embodiment.PREFIX}gripper_{s}_joint_{n}").qposadr[0]
                    for n, _ in embodiment.GRIPPER_COUPLING
                ]
                for s in ("left", "right")
            ]
        )
        self._finger_coef = np.array([c for _, c in embodiment.GRIPPER_COUPLING])
        act = [model.actuator(j).id for j in robot.actuated_joints]
        grip = [model.actuator(f"{embodiment.PREFIX}gripper_{s}").id for s in ("left", "right")]
        # action index -> actuator index
        self._act_of_action = np.array(act[:7] + [grip[0]] + act[7:14] + [grip[1]] + act[14:16])
        # velocity actuators of torso yaw and head pitch (control: the reference's velocity)
        self._vel_act = np.array(
            [
                model.actuator(f"{j}_velocity").id
                for j in (embodiment.TORSO_YAW_JOINT, embodiment.HEAD_PITCH_JOINT)
            ]
        )
        self.action_low = np.zeros(ACTION_DIM)
        self.action_high = np.ones(ACTION_DIM)
        ranges = np.array([model.joint(j).range for j in robot.actuated_joints])
        self.action_low[self._joint_idx], self.action_high[self._joint_idx] = ranges[:, 0], ranges[:, 1]
        self.controller = JointTargetController(SUBSTEPS, model.opt.timestep)
        self.head_cam_id = model.camera(embodiment.HEAD_CAMERA).id
        self.head_K = intrinsics(float(model.cam_fovy[self.head_cam_id]), self.image_width, self.image_height)
        self._renderers: dict[tuple[int, int], mujoco.Renderer] = {}
        self.visibility_checker = head_visibility_checker(
            model, info.objects, self.image_height, self.image_width
        )
        self.last_clip: ClipReport | None = None
        self.clip_count = 0
        self.reset()

    # ---- state -------------------------------------------------------------------------------
    def home_action(self) -> np.ndarray:
        a = np.zeros(ACTION_DIM)
        home = embodiment.home_arm(self.info.workspace.two_level)
        a[LEFT_ARM], a[RIGHT_ARM] = home["left"], home["right"]
        a[LEFT_GRIPPER] = a[RIGHT_GRIPPER] = 1.0
        a[TORSO_YAW], a[HEAD_PITCH] = embodiment.HOME_TORSO_YAW, embodiment.HOME_HEAD_PITCH
        return a

    def reset(self, start: np.ndarray | None = None) -> None:
        """Objects at their spawn poses, robot at ``start`` (default: home) with matching targets."""
        mujoco.mj_resetData(self.model, self.data)
        start = self.home_action() if start is None else validate_action(start)
        self._set_joint_state(start)
        self.data.ctrl[:] = self._ctrl_from_reference(start)
        self.controller.reset(start)
        mujoco.mj_forward(self.model, self.data)

    def _set_joint_state(self, a: np.ndarray) -> None:
        self.data.qpos[self._joint_qadr] = a[self._joint_idx]
        q = self._gripper_to_joint(a[self._grip_idx])
        self.data.qpos[self._grip_qadr] = q
        self.data.qpos[self._finger_qadr] = q[:, None] * self._finger_coef

    @staticmethod
    def _gripper_to_joint(g):
        return embodiment.GRIPPER_CLOSED_RAD * (1.0 - np.asarray(g))

    def state(self) -> np.ndarray:
        s = np.zeros(ACTION_DIM)
        s[self._joint_idx] = self.data.qpos[self._joint_qadr]
        s[self._grip_idx] = np.clip(
            1.0 - self.data.qpos[self._grip_qadr] / embodiment.GRIPPER_CLOSED_RAD, 0.0, 1.0
        )
        return s

    # ---- control -----------------------------------------------------------------------------
    def _ctrl_from_reference(self, ref: np.ndarray, velocity=(0.0, 0.0)) -> np.ndarray:
        """Actuator controls for 18-D references ``ref`` (..., 18) and torso-yaw / head-pitch
        reference velocities (..., 2)."""
        ctrl = np.zeros(ref.shape[:-1] + (self.model.nu,))
        ctrl[..., self._vel_act] = velocity
        ctrl[..., self._act_of_action] = ref
        ctrl[..., self._act_of_action[self._grip_idx]] = self._gripper_to_joint(ref[..., self._grip_idx])
        return ctrl

    def step(self, action) -> ClipReport:
        """Apply one 15 Hz action (absolute joint targets). Out-of-range entries are clipped to the
        joint limits and reported in the returned ``ClipReport`` (and logged)."""
        a = validate_action(action)
        a, report = clip_action(a, self.action_low, self.action_high)
        if report.any:
            self.clip_count += 1
            (log.warning if self.clip_count == 1 else log.debug)(
                "action clipped to joint limits (requested, applied): %s%s",
                report.as_dict(),
                "; further clips are reported in step() results and logged at DEBUG"
                if self.clip_count == 1
                else "",
            )
        refs, velocity = self.controller.substep_targets(a)
        for ctrl in self._ctrl_from_reference(refs, velocity):
            self.data.ctrl[:] = ctrl
            mujoco.mj_step(self.model, self.data)
        self.last_clip = report
        return report

    # ---- sensing -----------------------------------------------------------------------------
    def _renderer(self, width: int, height: int) -> mujoco.Renderer:
        key = (width, height)
        if key not in self._renderers:
            try:
                self._renderers[key] = mujoco.Renderer(self.model, height=height, width=width)
            except Exception as exc:  # GL context creation failures surface here
                raise rendering_error(exc) from exc
        return self._renderers[key]

    def render_head(self) -> np.ndarray:
        r = self._renderer(self.image_width, self.image_height)
        r.update_scene(self.data, camera=self.head_cam_id, scene_option=self._draw)
        return r.render()

    def render_wrist(self, side: str) -> np.ndarray:
        if not self.info.wrist_cameras:
            raise ValueError("wrist cameras are off; build the scene with SceneBuilder(wrist_cameras=True)")
        r = self._renderer(WRIST_WIDTH, WRIST_HEIGHT)
        r.update_scene(self.data, camera=embodiment.WRIST_CAMERAS[side], scene_option=self._draw)
        return r.render()

    def head_camera(self) -> dict[str, np.ndarray]:
        return {
            "intrinsic_cv": self.head_K.copy(),
            "extrinsic_cv": extrinsic_cv(self.data, self.head_cam_id),
            "cam2world_gl": cam2world_gl(self.data, self.head_cam_id),
        }

    def end_effector_poses(self) -> dict[str, np.ndarray]:
        """TCP position and orientation quaternion (w, x, y, z) per arm."""
        out = {}
        for side, site in embodiment.TCP_SITES.items():
            q = np.zeros(4)
            mujoco.mju_mat2Quat(q, self.data.site(site).xmat)
            out[side] = np.concatenate([self.data.site(site).xpos, q])
        return out

    def visibility(self) -> Visibility:
        return self.visibility_checker(self.data)

    def close(self) -> None:
        for r in self._renderers.values():
            r.close()
        self._renderers.clear()
