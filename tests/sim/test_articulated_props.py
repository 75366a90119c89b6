"""Articulated and information-bearing props: push button, bell, back-patch block, digit labels."""

import mujoco
import numpy as np

from lerobot_activearena.sim.assets.devices import BUTTON_PRESSED, BUTTON_RESET, digit_image
from lerobot_activearena.sim.assets.handheld import add_patch_block
from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim


def _sim():
    b = SceneBuilder()
    b.add_object("button", "button_2", 0.45, 90.0, number=2)
    b.add_object("bell", "bell", 0.45, 60.0)
    b.add_object("patch_block", "gray_block", 0.45, 120.0, patch_color="blue")
    model, info = b.compile()
    return ActiveArenaSim(model, info)


def _push(sim, body, force, steps):
    bid = sim.model.body(body).id
    for _ in range(steps):
        sim.data.xfrc_applied[bid] = [0, 0, -force, 0, 0, 0]
        sim.step(sim.home_action())
    sim.data.xfrc_applied[bid] = 0


def test_button_presses_under_a_push_and_springs_back():
    sim = _sim()
    for _ in range(10):
        sim.step(sim.home_action())
    q = lambda: sim.data.joint("button_2_joint").qpos[0]  # noqa: E731
    assert q() > BUTTON_RESET, "a button at rest must read as reset"
    _push(sim, "button_2_cap", 5.0, 8)
    assert q() < BUTTON_PRESSED
    for _ in range(10):
        sim.step(sim.home_action())
    assert q() > BUTTON_RESET


def test_bell_plunger_presses_and_returns():
    sim = _sim()
    q = lambda: sim.data.joint("bell_plunger_joint").qpos[0]  # noqa: E731
    _push(sim, "bell_plunger", 8.0, 8)
    assert q() < -0.004
    for _ in range(10):
        sim.step(sim.home_action())
    assert q() > -0.001


def test_patch_block_matches_the_paper_dimensions():
    spec = mujoco.MjSpec()
    info = add_patch_block(spec, "b", (0, 0, 0), patch_color="green")
    m = spec.compile()
    np.testing.assert_allclose(m.geom("b_body").size, [0.024] * 3)
    np.testing.assert_allclose(m.geom("b_patch").size, [0.0015, 0.012, 0.012])
    outer = m.geom("b_patch").pos[0] + 0.0015
    assert abs(outer - (0.024 + 0.00005)) < 1e-9  # protrudes 0.05 mm
    assert info.attributes["patch_color"] == "green"


def test_digit_labels_differ():
    imgs = [digit_image(str(n)) for n in (1, 2, 3)]
    assert all(i.shape == (64, 64, 3) and i.dtype == np.uint8 for i in imgs)
    assert not np.array_equal(imgs[0], imgs[1]) and not np.array_equal(imgs[1], imgs[2])
    assert (imgs[0] < 100).any(), "the digit is drawn in dark ink"
