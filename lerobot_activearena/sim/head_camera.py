"""Head-camera facts shared by the simulator, the scene sampler and the success checks: the
visibility checker of the head image, whether an object's information face is seen, and the search
views (torso yaw, head pitch) that together cover the fan."""

from __future__ import annotations

import mujoco
import numpy as np

from . import embodiment
from .assets.base import ObjectInfo
from .scene import HEAD_HEIGHT, HEAD_WIDTH
from .visibility import VisibilityChecker, surface_point_visible

HEAD_BODY = f"{embodiment.PREFIX}head_link_2"  # the camera's own body: never an occluder
SEARCH_PITCH = 1.0  # rad: the home pitch
# (torso yaw, head pitch) of the three search sectors: headings 90, 36 and 144 deg
SEARCH_VIEWS = ((0.0, SEARCH_PITCH), (-0.95, SEARCH_PITCH), (0.95, SEARCH_PITCH))
UPPER_SEARCH_PITCH = 0.47  # rad: the head pitched up to the upper band (the release's ID value)
UPPER_SEARCH_VIEWS = tuple((yaw, UPPER_SEARCH_PITCH) for yaw, _ in SEARCH_VIEWS)


def validate_head_size(height: int, width: int) -> tuple[int, int]:
    """``(height, width)`` of the head image, checked: positive and in the camera's 3:4 shape. The
    60 deg vertical field of view is fixed, so a 3:4 image at any size sees the same scene (the
    intrinsics scale with it, visibility is a fraction of the projected box) while another shape
    would widen or narrow the horizontal view and change the benchmark."""
    h, w = int(height), int(width)
    if h != height or w != width or h < 1 or w < 1:
        raise ValueError(f"head image size must be positive integers, got {height}x{width}")
    if h * HEAD_WIDTH != w * HEAD_HEIGHT:
        raise ValueError(
            f"head image {h}x{w} (height x width) is not 3:4 like the head camera's "
            f"{HEAD_HEIGHT}x{HEAD_WIDTH}; pick e.g. 96x128, 192x256 or 240x320"
        )
    return h, w


def search_views(workspace) -> tuple[tuple[float, float], ...]:
    """The search views of a workspace: the lower sectors at the home pitch, then (two-level) the
    same headings with the head pitched up to the upper band."""
    return SEARCH_VIEWS + (UPPER_SEARCH_VIEWS if workspace.two_level else ())


def head_visibility_checker(
    model: mujoco.MjModel, objects: list[ObjectInfo], height: int = HEAD_HEIGHT, width: int = HEAD_WIDTH
) -> VisibilityChecker:
    return VisibilityChecker(model, objects, embodiment.HEAD_CAMERA, width, height, exclude_body=HEAD_BODY)


def hidden_face_visible(model: mujoco.MjModel, data: mujoco.MjData, info: ObjectInfo) -> bool:
    """Whether the head camera sees object ``info``'s information face (its ``functional.info_face``:
    a back patch, a date label) right now: facing the camera, in the image and not occluded."""
    body = data.body(info.body)
    rot = body.xmat.reshape(3, 3)
    face = info.functional.info_face
    point = body.xpos + rot @ np.asarray(face.center)
    normal = rot @ np.asarray(face.normal)
    return surface_point_visible(
        model,
        data,
        model.camera(embodiment.HEAD_CAMERA).id,
        point,
        normal,
        model.geom(face.geom).id,
        HEAD_WIDTH,
        HEAD_HEIGHT,
        exclude_body=model.body(HEAD_BODY).id,
    )
