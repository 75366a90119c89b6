"""Success checks encode the instruction: events count only when the instructed arm's gripper does
them at the instructed part, state goals must hold for 8 frames with the robot off the objects, and
irreversible mistakes end the episode with a reason."""

import numpy as np
import pytest

from lerobot_activearena.envs.gym_env import ActiveArenaEnv
from lerobot_activearena.sim.simulator import ActiveArenaSim
from lerobot_activearena.tasks import get_task
from lerobot_activearena.tasks.sampling import sample_scene
from lerobot_activearena.tasks.success import STABLE_FRAMES, SuccessMonitor


def _sim(task_name, seed=0, split="id"):
    task = get_task(task_name)
    scene = sample_scene(task, seed, split)
    sim = ActiveArenaSim(scene.model, scene.info)
    return task, scene, sim, SuccessMonitor(task, sim, scene)


def _set_free_pose(sim, body, pos, quat=(1, 0, 0, 0)):
    j = sim.model.body(body).jntadr[0]
    adr = sim.model.jnt_qposadr[j]
    sim.data.qpos[adr : adr + 7] = [*pos, *quat]
    sim.data.qvel[sim.model.jnt_dofadr[j] : sim.model.jnt_dofadr[j] + 6] = 0


def test_a_plunger_dip_without_the_left_gripper_is_not_a_press():
    task, scene, sim, mon = _sim("click_bell_rotate_view")
    home = sim.home_action()
    for _ in range(STABLE_FRAMES + 2):
        sim.data.joint("bell_plunger_joint").qpos[0] = -0.007  # pushed down by nothing (e.g. a knock)
        sim.step(home)
        assert not mon.update()
    assert mon.checks["pressed_top_center_with_left_gripper"] is False
    assert mon.failed_checks == ["saw_task_objects", "pressed_top_center_with_left_gripper"]
    mon.observe(np.ones(len(scene.objects), bool))  # even once the bell has been seen
    sim.data.joint("bell_plunger_joint").qpos[0] = -0.007
    sim.step(home)
    assert not mon.update() and mon.failed_checks == ["pressed_top_center_with_left_gripper"]


def test_a_knocked_over_bell_ends_the_episode_with_a_reason():
    env = ActiveArenaEnv("click_bell_rotate_view", use_manifest=False, render_pixels=False)
    obs, _ = env.reset(seed=3)
    p = env.sim.data.body("bell").xpos.copy()
    _set_free_pose(env.sim, "bell", p + [0, 0, 0.05], quat=(np.cos(np.pi / 4), np.sin(np.pi / 4), 0, 0))
    for _ in range(10):
        obs, reward, terminated, truncated, info = env.step(obs["agent_pos"])
        if terminated:
            break
    assert terminated and not info["is_success"] and reward == 0.0
    assert info["failure_reason"] == "the bell was knocked over" and info["failure_state"] in (
        "DM",
        "CO",
        "CR",
    )
    env.close()


def test_pressing_a_wrong_button_is_an_irreversible_failure():
    task, scene, sim, mon = _sim("count_target_press_button", 3)
    right = scene.params["count"]
    wrong = 1 if right != 1 else 2
    sim.data.joint(f"button_{wrong}_joint").qpos[0] = -0.008
    assert not mon.update()
    assert mon.failure_reason == f"pressed button {wrong}; the count was {right}"
    sim.data.joint(f"button_{wrong}_joint").qpos[0] = 0.0
    assert not mon.update() and mon.failure_reason, "a failure is final"


def test_a_placed_cup_succeeds_only_after_resting_for_the_stable_frames():
    task, scene, sim, mon = _sim("place_empty_cup_rotate_view", 2)
    top = scene.obj("coaster").functional.support.top
    _set_free_pose(sim, "cup", sim.data.body("coaster").xpos + [0, 0, top + 0.001])
    mon.observe(np.ones(len(scene.objects), bool))
    home = sim.home_action()
    reported = []
    for _ in range(STABLE_FRAMES + 4):
        sim.step(home)
        reported.append(mon.update())
    assert mon.checks == {
        "saw_task_objects": True,
        "cup_on_coaster": True,
        "cup_upright": True,
        "cup_released": True,
    }
    assert reported.index(True) == STABLE_FRAMES - 1, reported


def test_a_placed_cup_the_camera_never_saw_is_not_a_success():
    task, scene, sim, mon = _sim("place_empty_cup_rotate_view", 2)
    _set_free_pose(
        sim,
        "cup",
        sim.data.body("coaster").xpos + [0, 0, scene.obj("coaster").functional.support.top + 0.001],
    )
    for _ in range(STABLE_FRAMES + 4):
        sim.step(sim.home_action())
        assert not mon.update()
    assert mon.failed_checks == ["saw_task_objects"]


def test_a_tipped_cup_on_the_coaster_is_not_placed():
    task, scene, sim, mon = _sim("place_empty_cup_rotate_view", 2)
    top = scene.obj("coaster").functional.support.top
    tilt = np.radians(40) / 2
    _set_free_pose(
        sim,
        "cup",
        sim.data.body("coaster").xpos + [0, 0, top + 0.03],
        quat=(np.cos(tilt), np.sin(tilt), 0, 0),
    )
    for _ in range(STABLE_FRAMES + 4):
        sim.step(sim.home_action())
        assert not mon.update()
    assert not mon.checks["cup_upright"]


def test_a_task_object_off_the_table_ends_the_episode():
    task, scene, sim, mon = _sim("check_block_color", 1)
    _set_free_pose(sim, "gray_block", (0.0, -0.6, 0.3))
    sim.step(sim.home_action())
    assert not mon.update() and mon.failure_reason == "gray_block fell off the table"


def test_the_expert_that_cannot_look_around_fails_its_episode_not_the_run():
    """--env.fixed_view=true with the expert channel: the expert never finds what it needs; the
    episode ends as a failure (DM), the env keeps working."""
    env = ActiveArenaEnv(
        "count_target_press_button", split="id", fixed_view=True, expert_channel=True, render_pixels=False
    )
    obs, _ = env.reset(seed=env.seed_base)
    for _ in range(env._max_episode_steps):
        obs, reward, terminated, truncated, info = env.step(obs["environment_state"])
        if terminated or truncated:
            break
    assert not info["is_success"] and info["failure_state"] == "DM"
    env.close()


def test_subtask_marker_follows_declaration_order():
    from lerobot_activearena.expert.context import ExpertContext

    ctx = ExpertContext.__new__(ExpertContext)
    ctx.n_subtasks, ctx.intent = 2, type("I", (), {"subtask": 1})()
    with ctx.subtask(2):
        assert ctx.intent.subtask == 2
    with pytest.raises(ValueError, match="subtask 3 is not declared"), ctx.subtask(3):
        pass


def test_an_expert_that_crashes_fails_its_episode_in_the_env_not_the_run(monkeypatch, caplog):
    from lerobot_activearena.tasks.inventory.click_bell_rotate_view import ClickBellRotateView

    def broken(self, ctx, scene):
        yield ctx.emit()
        raise IndexError("a bug in a task script")

    monkeypatch.setattr(ClickBellRotateView, "expert", broken)
    env = ActiveArenaEnv(
        "click_bell_rotate_view", use_manifest=False, expert_channel=True, render_pixels=False
    )
    obs, _ = env.reset(seed=2)
    for _ in range(3):
        obs, *_ = env.step(obs["environment_state"])
    assert env.expert_gave_up == "expert crashed: IndexError: a bug in a task script"
    assert "the click_bell_rotate_view expert crashed" in caplog.text
    env.close()
