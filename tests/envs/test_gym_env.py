"""The gym env over the task registry: observation contract, manifests, fixed view, failure states,
and the LeRobot EnvConfig's task suites."""

import importlib
import json

import numpy as np
import pytest

from lerobot_activearena.envs.configs import ActiveArenaEnvConfig
from lerobot_activearena.envs.gym_env import ActiveArenaEnv
from lerobot_activearena.envs.manifests import PROTOCOL_EPISODES, load_manifest
from lerobot_activearena.episodes.episode import failure_state


def test_reset_step_observation_contract():
    env = ActiveArenaEnv("click_bell_rotate_view", use_manifest=False)
    obs, info = env.reset(seed=1)
    assert info["scene_seed"] == 1
    assert obs["pixels"]["head"].shape == (384, 512, 3) and obs["pixels"]["head"].dtype == np.uint8
    assert obs["agent_pos"].shape == (18,) and obs["agent_pos"].dtype == np.float32
    assert env.observation_space.contains(obs)
    assert env.metadata["render_fps"] == 15
    assert env.task_description == "Press the bell's top center using the left arm."
    assert env.task == "click_bell_rotate_view" and env._max_episode_steps == 137
    obs2, reward, terminated, truncated, info = env.step(obs["agent_pos"])
    assert info["is_success"] is False and reward == 0.0 and not terminated and not truncated
    np.testing.assert_allclose(obs2["agent_pos"], obs["agent_pos"], atol=2e-3)
    env.close()


def test_unknown_task_and_step_before_reset_are_clear_errors():
    with pytest.raises(ValueError, match="unknown ActiveArena task"):
        ActiveArenaEnv(task="nope")
    env = ActiveArenaEnv()
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(18, np.float32))
    with pytest.raises(ValueError, match="--env.split"):
        ActiveArenaEnvConfig(split="test")


def test_manifest_seeds_are_played_in_order():
    env = ActiveArenaEnv("count_target_press_button", split="ood")
    seeds = load_manifest("count_target_press_button", "ood")
    assert len(seeds) == 100 and len(set(seeds)) == 100 and PROTOCOL_EPISODES == 50
    for k in (0, 7):
        _, info = env.reset(seed=1000 + k)
        assert info["scene_seed"] == seeds[k]
    with pytest.raises(IndexError, match="outside the 100-seed manifest"):
        env.reset(seed=1000 + 100)
    env.close()


def test_fixed_view_holds_head_and_torso_at_home():
    for fixed, moved in ((True, False), (False, True)):
        env = ActiveArenaEnv("click_bell_rotate_view", fixed_view=fixed, use_manifest=False)
        obs, _ = env.reset(seed=2)
        a = obs["agent_pos"].copy()
        a[16], a[17] = 0.6, 0.5
        for _ in range(10):
            obs, *_ = env.step(a)
        turned = abs(obs["agent_pos"][16]) > 0.3 and abs(obs["agent_pos"][17] - 1.0) > 0.3
        assert turned == moved
        env.close()


def test_failure_states():
    yes, no = np.array([1, 1], bool), np.array([1, 0], bool)
    assert failure_state(True, no, no) == ""
    assert failure_state(False, no, no) == "DM"
    assert failure_state(False, yes, no) == "CO"
    assert failure_state(False, yes, yes) == "CR"


def test_idle_episode_ends_as_dm_when_the_target_was_never_seen(tmp_path):
    env = ActiveArenaEnv(
        "click_bell_rotate_view", use_manifest=False, episode_log_dir=str(tmp_path), max_episode_steps=3
    )
    obs, _ = env.reset(seed=1004)
    for _ in range(3):
        obs, _, terminated, truncated, info = env.step(obs["agent_pos"])
    assert truncated and not terminated and info["failure_state"] == "DM"
    env.close()
    (log,) = tmp_path.glob("click_bell_rotate_view_id_*.jsonl")
    rec = json.loads(log.read_text())
    assert rec["episode"] == 4 and rec["scene_seed"] == 1004 and rec["failure_state"] == "DM"
    assert rec["steps"] == 3 and len(rec["view_targets"]) == 3 and not rec["success"]


def test_config_builds_category_suites_of_task_envs():
    cfg = ActiveArenaEnvConfig(task="count_target_press_button,click_bell_rotate_view", split="ood")
    suites = cfg.create_envs(n_envs=2)
    assert set(suites) == {"MD", "SS"}  # grouped by the paper's category
    assert list(suites["SS"]) == ["click_bell_rotate_view"] and list(suites["MD"]) == [
        "count_target_press_button"
    ]
    vec = suites["SS"]["click_bell_rotate_view"]
    assert vec.num_envs == 2
    assert vec.call("split") == ("ood", "ood")
    for group in suites.values():
        for v in group.values():
            v.close()
    lazy = ActiveArenaEnvConfig(task="SS").create_envs(n_envs=2, use_async_envs=True)["SS"][
        "click_bell_rotate_view"
    ]
    assert lazy._env is None, "async workers start only when the suite is evaluated"
    lazy.close()
    # the fork server preloads (and silently skips a wrong name) what a worker unpickles: the env and its wrapper
    from lerobot_activearena.envs.configs import FORKSERVER_PRELOAD

    preloaded = [importlib.import_module(name) for name in FORKSERVER_PRELOAD]
    from lerobot.envs.utils import freeze_after_episode_end

    assert {freeze_after_episode_end.__module__, ActiveArenaEnv.__module__} <= {m.__name__ for m in preloaded}


@pytest.mark.parametrize("blowup", ["nan_velocity", "huge_velocity"])
def test_a_physics_blowup_ends_the_episode_as_a_failure_for_any_policy(blowup, tmp_path):
    env = ActiveArenaEnv("click_bell_rotate_view", render_pixels=False, episode_log_dir=str(tmp_path))
    obs, _ = env.reset(seed=env.seed_base)
    obs, *_ = env.step(obs["agent_pos"])
    if blowup == "nan_velocity":
        env.sim.data.qvel[:] = np.nan
    else:
        env.sim.data.qvel[-6:] = 1e9  # a free object flung: MuJoCo finds a diverging acceleration
    obs, reward, terminated, truncated, info = env.step(obs["agent_pos"])
    assert terminated and not truncated and reward == 0.0 and info["is_success"] is False
    assert info["failure_reason"].startswith("physics: the simulation diverged"), info["failure_reason"]
    assert np.isfinite(obs["agent_pos"]).all()
    # the outcome stays: further steps (a batch waiting for its other envs) change nothing
    obs, _, terminated, _, info = env.step(obs["agent_pos"])
    assert terminated and info["failure_reason"].startswith("physics:")
    rec = json.loads(next(tmp_path.glob("*.jsonl")).read_text().splitlines()[0])
    assert rec["failure_reason"].startswith("physics:") and not rec["success"] and rec["steps"] == 2
    env.close()


def test_step_limit_is_a_constructor_argument():
    assert ActiveArenaEnv("click_bell_rotate_view")._max_episode_steps == 137
    assert ActiveArenaEnv("click_bell_rotate_view", max_episode_steps=5)._max_episode_steps == 5
    with pytest.raises(ValueError, match="max_episode_steps must be >= 1"):
        ActiveArenaEnv("click_bell_rotate_view", max_episode_steps=0)
    vec = ActiveArenaEnvConfig(task="click_bell_rotate_view", episode_length=7).create_envs(1)["SS"][
        "click_bell_rotate_view"
    ]
    assert vec.call("_max_episode_steps") == (7,)
    vec.close()
