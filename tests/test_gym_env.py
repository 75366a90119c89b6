import numpy as np
import pytest

from lerobot_activearena.envs.gym_env import ActiveArenaEnv


def test_reset_step_observation_contract():
    env = ActiveArenaEnv()
    obs, info = env.reset(seed=1)
    assert obs["pixels"]["head"].shape == (384, 512, 3) and obs["pixels"]["head"].dtype == np.uint8
    assert obs["agent_pos"].shape == (18,) and obs["agent_pos"].dtype == np.float32
    assert env.observation_space.contains(obs)
    assert env.metadata["render_fps"] == 15 and env.task_description == "pick up the red can"
    obs2, reward, terminated, truncated, info = env.step(obs["agent_pos"])
    assert info["is_success"] is False and reward == 0.0 and not terminated
    np.testing.assert_allclose(obs2["agent_pos"], obs["agent_pos"], atol=2e-3)
    env.close()


def test_unknown_task_is_a_clear_error():
    with pytest.raises(ValueError, match="unknown ActiveArena task"):
        ActiveArenaEnv(task="nope")


def test_step_before_reset_is_a_clear_error():
    env = ActiveArenaEnv()
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(18, np.float32))
    env.close()
