import logging

import numpy as np
import pytest

from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim


@pytest.fixture(scope="module")
def sim():
    model, info = SceneBuilder().compile()
    return ActiveArenaSim(model, info)


def test_bad_actions_raise_clear_errors(sim):
    with pytest.raises(ValueError, match=r"shape \(18,\)"):
        sim.step(np.zeros(16))
    with pytest.raises(ValueError, match="non-finite"):
        a = sim.home_action()
        a[3] = np.nan
        sim.step(a)
    with pytest.raises(TypeError, match="dtype"):
        sim.step(np.array(["x"] * 18))


def test_out_of_range_targets_are_clipped_and_reported(sim, caplog):
    sim.reset()
    a = sim.home_action()
    a[16] = 2.0  # torso yaw limit is 1.2
    a[7] = 1.5  # gripper command is in [0, 1]
    with caplog.at_level(logging.WARNING):
        report = sim.step(a)
    d = report.as_dict()
    assert d["torso_yaw"] == (2.0, 1.2) and d["left_gripper"] == (1.5, 1.0)
    assert "clipped" in caplog.text
    for _ in range(30):
        sim.step(a)
    assert sim.state()[16] == pytest.approx(1.2, abs=0.02)


def test_torso_and_head_respect_velocity_limits(sim):
    sim.reset()
    a = sim.home_action()
    a[16], a[17] = 1.2, -1.2
    prev = sim.state()
    torso_v, head_v = [], []
    for _ in range(30):
        sim.step(a)
        s = sim.state()
        torso_v.append(abs(s[16] - prev[16]) * 15)
        head_v.append(abs(s[17] - prev[17]) * 15)
        prev = s
    assert max(torso_v) <= 2.5 * 1.05 and max(head_v) <= 10.0 * 1.05
    assert sim.state()[16] == pytest.approx(1.2, abs=0.02)
    assert sim.state()[17] == pytest.approx(-1.2, abs=0.02)
    # 1.2 rad at 2.5 rad/s cannot be done in under 0.48 s: the limiter must have slowed it.
    assert sum(v > 0.1 for v in torso_v) >= 7
