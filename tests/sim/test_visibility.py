"""Visibility against scenes where the answer is known."""

import math

import numpy as np
import pytest

from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim


def _sim(objects):
    b = SceneBuilder()
    for kind, name, pos, params in objects:
        b.add_object_at(kind, name, pos, **params)
    model, info = b.compile()
    return ActiveArenaSim(model, info)


def _vis(sim, name):
    v = sim.visibility()
    i = [o.name for o in sim.info.objects].index(name)
    return v.visible[i], v.visible_fraction[i], v.in_image_fraction[i], v.unoccluded_fraction[i], v.uv_norm[i]


def _ray_point(sim, u, v, depth):
    """World point at pixel (u, v) and camera depth ``depth`` (OpenCV convention)."""
    cam = sim.head_camera()
    intrinsic_matrix, cv2world = cam["intrinsic_cv"], np.linalg.inv(cam["extrinsic_cv"])
    fx, fy = intrinsic_matrix[0, 0], intrinsic_matrix[1, 1]
    cx, cy = intrinsic_matrix[0, 2], intrinsic_matrix[1, 2]
    pc = np.array([(u - cx) / fx * depth, (v - cy) / fy * depth, depth, 1.0])
    return (cv2world @ pc)[:3]


def test_object_in_view_is_visible_with_centred_uv():
    probe = _sim([])
    p = _ray_point(probe, 256, 192, 0.45)  # in mid-air, above the table
    sim = _sim([("ball", "ball", p - [0, 0, 0.03], {"radius": 0.03})])
    visible, frac, in_img, unocc, uv = _vis(sim, "ball")
    assert visible and in_img == pytest.approx(1.0) and unocc > 0.95
    np.testing.assert_allclose(uv, [0.5, 0.5], atol=0.02)


def test_object_behind_the_view_is_not_visible():
    # 90 deg to the robot's right, on the floor: outside the head camera's field of view.
    sim = _sim([("ball", "ball", (1.0, -0.2, 0.0), {})])
    visible, frac, in_img, _, uv = _vis(sim, "ball")
    assert not visible and in_img == 0.0 and tuple(uv) == (-1.0, -1.0)


@pytest.mark.parametrize("inside, lo, hi, expect", [(0.6, 0.4, 0.9, True), (0.1, 0.0, 0.4, False)])
def test_object_partly_outside_the_image(inside, lo, hi, expect):
    probe = _sim([])
    half = 0.04
    # Put a cube at the right image border so that ``inside`` of its width is in the image.
    depth = 0.45
    px_per_m = probe.head_camera()["intrinsic_cv"][0, 0] / depth
    u_center = 512 + (0.5 - inside) * 2 * half * px_per_m
    p = _ray_point(probe, u_center, 192, depth)
    cam_yaw = probe.head_camera()["cam2world_gl"][:3, 0]
    yaw = math.atan2(cam_yaw[1], cam_yaw[0])
    sim = _sim([("block", "cube", p - [0, 0, half], {"half": (half, half, half), "yaw": yaw})])
    visible, frac, in_img, unocc, _ = _vis(sim, "cube")
    # The projected box of a cube seen from above is wider than its front face: check a band.
    assert lo < in_img < hi
    assert visible == expect


def test_object_occluded_behind_a_box_is_not_visible():
    probe = _sim([])
    ball = _ray_point(probe, 256, 192, 0.5)
    wall = _ray_point(probe, 256, 192, 0.3)
    sim = _sim(
        [
            ("ball", "ball", ball - [0, 0, 0.03], {"radius": 0.03}),
            ("block", "wall", wall - [0, 0, 0.1], {"half": (0.12, 0.12, 0.1)}),
        ]
    )
    visible, frac, in_img, unocc, _ = _vis(sim, "ball")
    assert in_img == pytest.approx(1.0) and unocc < 0.05 and not visible
    assert _vis(sim, "wall")[0]
