"""Pinhole camera parameters of MuJoCo cameras in the paper's conventions."""

from __future__ import annotations

import math

import mujoco
import numpy as np

_GL_TO_CV = np.diag([1.0, -1.0, -1.0])


def intrinsics(fovy_deg: float, width: int, height: int) -> np.ndarray:
    """3x3 intrinsics of an ideal pinhole with square pixels (MuJoCo's model)."""
    f = 0.5 * height / math.tan(math.radians(fovy_deg) / 2)
    return np.array([[f, 0.0, width / 2], [0.0, f, height / 2], [0.0, 0.0, 1.0]])


def cam2world_gl(data: mujoco.MjData, cam_id: int) -> np.ndarray:
    """4x4 camera-to-world, OpenGL convention (x right, y up, looking along -z)."""
    pose = np.eye(4)
    pose[:3, :3] = data.cam_xmat[cam_id].reshape(3, 3)
    pose[:3, 3] = data.cam_xpos[cam_id]
    return pose


def extrinsic_cv(data: mujoco.MjData, cam_id: int) -> np.ndarray:
    """4x4 world-to-camera, OpenCV convention (x right, y down, looking along +z)."""
    rot = data.cam_xmat[cam_id].reshape(3, 3) @ _GL_TO_CV
    pose = np.eye(4)
    pose[:3, :3] = rot.T
    pose[:3, 3] = -rot.T @ data.cam_xpos[cam_id]
    return pose


def project(
    points_world: np.ndarray, intrinsic_matrix: np.ndarray, world_to_cam: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Project Nx3 world points; returns pixel coords (N,2) and camera depths (N,)."""
    pc = points_world @ world_to_cam[:3, :3].T + world_to_cam[:3, 3]
    z = pc[:, 2]
    focal = np.array([intrinsic_matrix[0, 0], intrinsic_matrix[1, 1]])
    principal_point = np.array([intrinsic_matrix[0, 2], intrinsic_matrix[1, 2]])
    with np.errstate(divide="ignore", invalid="ignore"):
        uv = (pc[:, :2] / z[:, None]) * focal + principal_point
    return uv, z
