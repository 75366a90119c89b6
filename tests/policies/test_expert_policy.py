"""The `activearena_expert` oracle policy: the env's opt-in privileged channel and a real
lerobot-eval run."""

import json
from pathlib import Path

import pytest

from lerobot_activearena.envs.gym_env import ActiveArenaEnv
from lerobot_activearena.envs.manifests import load_manifest


@pytest.mark.parametrize("task,seed", [("click_bell_rotate_view", 3), ("check_block_color", 5)])
def test_expert_channel_played_through_the_env_succeeds(task, seed):
    env = ActiveArenaEnv(task, split="ood", use_manifest=False, expert_channel=True)
    obs, _ = env.reset(seed=seed)
    for _ in range(env._max_episode_steps):
        obs, _, terminated, truncated, info = env.step(obs["environment_state"])
        if terminated or truncated:
            break
    assert info["is_success"] and info["failure_state"] == ""
    env.close()


def test_privileged_channel_is_off_by_default():
    env = ActiveArenaEnv("click_bell_rotate_view", use_manifest=False)
    obs, _ = env.reset(seed=0)
    assert "environment_state" not in obs and "environment_state" not in env.observation_space.spaces
    env.close()


def test_policy_refuses_to_run_without_the_channel():
    from lerobot.configs.types import FeatureType, PolicyFeature

    from lerobot_activearena.policies.activearena_expert import ActiveArenaExpertConfig

    cfg = ActiveArenaExpertConfig()
    cfg.input_features = {"observation.state": PolicyFeature(type=FeatureType.STATE, shape=(18,))}
    with pytest.raises(ValueError, match="--env.expert_channel=true"):
        cfg.validate_features()


def test_lerobot_eval_runs_the_oracle_on_manifest_seeds(tmp_path):
    """LeRobot's eval entry point, in process (the CLI itself: test_plugin_discovery.py)."""
    from lerobot.configs.default import EvalConfig
    from lerobot.configs.eval import EvalPipelineConfig
    from lerobot.scripts.lerobot_eval import eval_main

    from lerobot_activearena.envs.configs import ActiveArenaEnvConfig
    from lerobot_activearena.policies.activearena_expert import ActiveArenaExpertConfig

    env = ActiveArenaEnvConfig(
        task="click_bell_rotate_view",
        expert_channel=True,
        episode_log_dir=str(tmp_path / "eval" / "episodes"),
    )
    cfg = EvalPipelineConfig(
        env=env,
        policy=ActiveArenaExpertConfig(device="cpu"),
        eval=EvalConfig(n_episodes=3, batch_size=2),
        output_dir=tmp_path / "eval",
    )
    eval_main(cfg)
    info = json.loads((tmp_path / "eval" / "eval_info.json").read_text())
    assert info["overall"]["pc_success"] == 100.0 and info["overall"]["n_episodes"] == 3
    assert "SS" in info["per_group"]
    assert info["per_task"][0]["task_id"] == "click_bell_rotate_view"
    assert all(Path(p).exists() for p in info["overall"]["video_paths"])
    # Episodes 0, 1, 2 played manifest seeds 0, 1, 2 although they ran in batches of 2.
    logs = [
        json.loads(line)
        for f in (tmp_path / "eval" / "episodes").glob("*.jsonl")
        for line in f.read_text().splitlines()
    ]
    played = sorted((e["episode"], e["scene_seed"]) for e in logs)
    manifest = load_manifest("click_bell_rotate_view", "id")
    assert [s for _, s in played][:3] == manifest[:3] and [k for k, _ in played][:3] == [0, 1, 2]
