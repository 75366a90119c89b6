import numpy as np
import pytest

from lerobot_activearena.sim.camera import project
from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim


@pytest.fixture(scope="module")
def sim():
    b = SceneBuilder()
    b.add_object("ball", "red_ball", 0.55, 90.0, radius=0.03, rgba=(1.0, 0.0, 0.0, 1.0))
    model, info = b.compile()
    return ActiveArenaSim(model, info)


def test_head_intrinsics_match_paper(sim):
    intrinsic_matrix = sim.head_camera()["intrinsic_cv"]
    assert intrinsic_matrix[0, 0] == pytest.approx(332.55, abs=0.01)
    assert intrinsic_matrix[1, 1] == pytest.approx(332.55, abs=0.01)
    assert (intrinsic_matrix[0, 2], intrinsic_matrix[1, 2]) == (256.0, 192.0)
    assert sim.render_head().shape == (384, 512, 3)


def test_extrinsics_are_inverse_conventions(sim):
    cam = sim.head_camera()
    extrinsic, gl2world = cam["extrinsic_cv"], cam["cam2world_gl"]
    cv2world = np.linalg.inv(extrinsic)
    np.testing.assert_allclose(cv2world[:3, 3], gl2world[:3, 3], atol=1e-9)
    np.testing.assert_allclose(cv2world[:3, :3], gl2world[:3, :3] @ np.diag([1, -1, -1]), atol=1e-9)


def test_projection_lands_on_rendered_object(sim):
    img = sim.render_head().astype(int)
    red = (img[..., 0] > 40) & (img[..., 0] > 3 * img[..., 1]) & (img[..., 0] > 3 * img[..., 2])
    assert red.sum() > 50, "the red ball in front of the robot should be in the head image"
    ys, xs = np.nonzero(red)
    center = sim.data.body("red_ball").xpos + np.array([0, 0, 0.03])
    cam = sim.head_camera()
    uv, z = project(center[None], cam["intrinsic_cv"], cam["extrinsic_cv"])
    assert z[0] > 0
    assert abs(uv[0, 0] - xs.mean()) < 3 and abs(uv[0, 1] - ys.mean()) < 3


def test_wrist_cameras_off_by_default_and_render_when_on(sim):
    with pytest.raises(ValueError, match="wrist cameras are off"):
        sim.render_wrist("left")
    model, info = SceneBuilder(wrist_cameras=True).compile()
    wrist = ActiveArenaSim(model, info)
    assert model.cam_fovy[model.camera("astribot_arm_left_effector").id] == pytest.approx(37.0)
    img = wrist.render_wrist("right")
    assert img.shape == (240, 320, 3) and img.std() > 1
    wrist.close()
