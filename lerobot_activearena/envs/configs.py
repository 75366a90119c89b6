"""LeRobot ``EnvConfig`` registered as ``activearena`` (``lerobot-eval --env.type=activearena``)."""

from __future__ import annotations

from dataclasses import dataclass, field

import gymnasium as gym
from lerobot.configs.types import FeatureType, PolicyFeature
from lerobot.envs.configs import EnvConfig
from lerobot.utils.constants import ACTION, OBS_IMAGES, OBS_STATE

from ..sim.action import ACTION_DIM
from ..sim.scene import CONTROL_HZ, HEAD_HEIGHT, HEAD_WIDTH


@EnvConfig.register_subclass("activearena")
@dataclass
class ActiveArenaEnvConfig(EnvConfig):
    task: str | None = "reference_pick_can"
    fps: int = CONTROL_HZ
    episode_length: int | None = None  # None: the task's own step limit
    features: dict[str, PolicyFeature] = field(default_factory=lambda: {
        ACTION: PolicyFeature(type=FeatureType.ACTION, shape=(ACTION_DIM,)),
        "agent_pos": PolicyFeature(type=FeatureType.STATE, shape=(ACTION_DIM,)),
        "pixels/head": PolicyFeature(type=FeatureType.VISUAL, shape=(HEAD_HEIGHT, HEAD_WIDTH, 3)),
    })
    features_map: dict[str, str] = field(default_factory=lambda: {
        ACTION: ACTION,
        "agent_pos": OBS_STATE,
        "pixels/head": f"{OBS_IMAGES}.head",
    })

    @property
    def gym_kwargs(self) -> dict:
        return {"task": self.task}

    def create_envs(self, n_envs: int, use_async_envs: bool = False) -> dict[str, dict[int, gym.vector.VectorEnv]]:
        from .gym_env import ActiveArenaEnv

        task = self.task

        def make():
            env = ActiveArenaEnv(task=task)
            limit = self.episode_length or env._max_episode_steps
            env._max_episode_steps = limit
            return gym.wrappers.TimeLimit(env, max_episode_steps=limit)

        cls = gym.vector.AsyncVectorEnv if (use_async_envs and n_envs > 1) else gym.vector.SyncVectorEnv
        kwargs = {"context": "forkserver"} if cls is gym.vector.AsyncVectorEnv else {}
        vec = cls([make for _ in range(n_envs)], **kwargs)
        return {"activearena": {0: vec}}
