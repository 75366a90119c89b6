import json
from importlib import resources

import mujoco
import numpy as np
import pytest

from lerobot_activearena.sim import embodiment
from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim


@pytest.fixture(scope="module")
def sim():
    model, info = SceneBuilder().compile()
    return ActiveArenaSim(model, info)


def _json_joints():
    tree = json.loads(
        resources.files("lerobot_activearena.sim").joinpath("data/astribot_s1_kinematics.json").read_text()
    )["tree"]
    out, stack = {}, [tree]
    while stack:
        n = stack.pop()
        out.update({j["name"]: j for j in n["joints"]})
        stack.extend(n["children"])
    return out


def test_official_names_and_18_controlled_joints(sim):
    m = sim.model
    for side in ("left", "right"):
        for j in embodiment.ARM_JOINTS[side]:
            assert m.joint(j).type == mujoco.mjtJoint.mjJNT_HINGE
    assert m.joint("astribot_torso_joint_4") and m.joint("astribot_head_joint_2")
    assert m.camera("astribot_head").id >= 0
    assert m.nu == 20  # 18 joint targets + velocity targets of torso yaw and head pitch
    # Torso joints 1-3 and head yaw are baked into the standing pose, not simulated.
    for fixed in embodiment.STANDING_POSE:
        with pytest.raises(KeyError):
            m.joint(fixed)


def test_joint_limits_follow_reference_and_paper(sim):
    ref = _json_joints()
    for side in ("left", "right"):
        for j in embodiment.ARM_JOINTS[side]:
            np.testing.assert_allclose(sim.model.joint(j).range, ref[j]["range"])
    np.testing.assert_allclose(sim.model.joint(embodiment.TORSO_YAW_JOINT).range, [-1.2, 1.2])
    np.testing.assert_allclose(sim.model.joint(embodiment.HEAD_PITCH_JOINT).range, [-1.22, 1.22])


def test_home_state_and_standing_geometry(sim):
    s = sim.state()
    np.testing.assert_allclose(s[:7], [-0.4, -0.7, -1.0, 1.4, -0.9, 0, 0], atol=1e-9)
    np.testing.assert_allclose(s[8:15], [0.4, -0.7, 1.0, 1.4, 0.9, 0, 0], atol=1e-9)
    assert s[16] == pytest.approx(0.0) and s[17] == pytest.approx(1.0)
    cam = sim.data.cam_xpos[sim.head_cam_id]
    assert 1.15 < cam[2] < 1.45, "head camera should stand 0.4-0.7 m over the 0.74 m table"
    fwd = -sim.data.cam_xmat[sim.head_cam_id].reshape(3, 3)[:, 2]
    assert fwd[1] > 0.4 and fwd[2] < -0.7, "at home the head looks forward (+y) and down at the table"


def test_robot_never_collides_with_itself(sim):
    m = sim.model
    robot = [g for g in range(m.ngeom) if m.body(m.geom_bodyid[g]).name.startswith("astribot_")]
    for a in robot:
        for b in robot:
            assert not (m.geom_contype[a] & m.geom_conaffinity[b]), (m.geom(a).name, m.geom(b).name)
    pads = [m.geom(f"astribot_gripper_{s}_pad_{f}") for s in ("left", "right") for f in "LR"]
    assert all(p.contype and p.priority[0] == 1 for p in pads)


def test_gripper_fingers_are_coupled_and_open_close(sim):
    sim.reset()
    a = sim.home_action()
    a[7] = 0.0  # close left
    for _ in range(10):
        sim.step(a)
    d = sim.data
    q = {n: d.joint(f"astribot_gripper_left_joint_{n}").qpos[0] for n in ("L1", "L11", "R1", "R11")}
    assert q["L1"] > 0.85
    assert q["L11"] == pytest.approx(q["L1"], abs=0.02) and q["R1"] == pytest.approx(q["L1"], abs=0.02)
    assert q["R11"] == pytest.approx(-q["L1"], abs=0.02)
    assert sim.state()[7] < 0.1 and sim.state()[15] > 0.95
    sim.reset()


def test_other_arm_is_the_other_side_and_names_a_wrong_one():
    assert [embodiment.other_arm(a) for a in embodiment.ARMS] == ["right", "left"]
    with pytest.raises(ValueError, match="arm must be one of"):
        embodiment.other_arm("middle")
