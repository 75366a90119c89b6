"""LeRobot ``EnvConfig`` registered as ``activearena`` (``lerobot-eval --env.type=activearena``)."""

from __future__ import annotations

import multiprocessing
from dataclasses import dataclass, field
from functools import partial

import gymnasium as gym
from lerobot.configs.types import FeatureType, PolicyFeature
from lerobot.envs.configs import EnvConfig
from lerobot.envs.utils import freeze_after_episode_end
from lerobot.utils.constants import ACTION, OBS_ENV_STATE, OBS_IMAGES, OBS_STATE

from ..sim.action import ACTION_DIM
from ..sim.head_camera import validate_head_size
from ..sim.scene import CONTROL_HZ, HEAD_HEIGHT, HEAD_WIDTH
from ..tasks.base import SPLITS
from .manifests import DEFAULT_SEED_BASE

# what an async env worker imports: loaded once in the fork server the workers start from
FORKSERVER_PRELOAD = ("lerobot.envs.utils", "lerobot_activearena.envs.gym_env")


@EnvConfig.register_subclass("activearena")
@dataclass
class ActiveArenaEnvConfig(EnvConfig):
    """``task``: a task name, a category (SS/SL/ML/MD/IA), ``all``, or a comma list of those.
    ``split``: ``id`` or ``ood``. ``fixed_view``: hold head pitch and torso yaw at home (the
    ActiveArena-Fixed ablation). Episodes play the task's seed manifest in order: episode k of
    lerobot-eval (seed ``seed_base + k``) uses manifest seed k; keep ``seed_base`` equal to
    lerobot-eval's ``--seed`` (both default to 1000). ``observation_height`` / ``observation_width``:
    the head image's size, 3:4 (default the paper's 384 x 512; e.g. 96 x 128 for CPU training),
    rendered at that size."""

    task: str = "all"
    split: str = "id"
    fixed_view: bool = False
    use_manifest: bool = True
    seed_base: int = DEFAULT_SEED_BASE
    expert_channel: bool = False  # privileged: the scripted expert's next action for `activearena_expert`
    episode_log_dir: str | None = None  # one JSON line per finished episode (failure states, view targets)
    fps: int = CONTROL_HZ
    observation_height: int = HEAD_HEIGHT
    observation_width: int = HEAD_WIDTH
    episode_length: int | None = None  # None: each task's own step limit
    render_pixels: bool = (
        True  # false: black head images, for policies that read none (the oracle); videos still render
    )
    features: dict[str, PolicyFeature] = field(
        default_factory=lambda: {
            ACTION: PolicyFeature(type=FeatureType.ACTION, shape=(ACTION_DIM,)),
            "agent_pos": PolicyFeature(type=FeatureType.STATE, shape=(ACTION_DIM,)),
            "pixels/head": PolicyFeature(type=FeatureType.VISUAL, shape=(HEAD_HEIGHT, HEAD_WIDTH, 3)),
        }
    )
    features_map: dict[str, str] = field(
        default_factory=lambda: {
            ACTION: ACTION,
            "agent_pos": OBS_STATE,
            "pixels/head": f"{OBS_IMAGES}.head",
        }
    )

    def __post_init__(self):
        if self.split not in SPLITS:
            raise ValueError(f"--env.split must be one of {SPLITS}, got {self.split!r}")
        try:
            size = validate_head_size(self.observation_height, self.observation_width)
        except ValueError as exc:
            raise ValueError(f"--env.observation_height / --env.observation_width: {exc}") from None
        self.features["pixels/head"] = PolicyFeature(type=FeatureType.VISUAL, shape=(*size, 3))
        if self.expert_channel:
            self.features["environment_state"] = PolicyFeature(type=FeatureType.ENV, shape=(ACTION_DIM,))
            self.features_map["environment_state"] = OBS_ENV_STATE

    @property
    def gym_kwargs(self) -> dict:
        return {
            "split": self.split,
            "fixed_view": self.fixed_view,
            "use_manifest": self.use_manifest,
            "seed_base": self.seed_base,
            "expert_channel": self.expert_channel,
            "episode_log_dir": self.episode_log_dir,
            "render_pixels": self.render_pixels,
            "max_episode_steps": self.episode_length,
            "observation_height": self.observation_height,
            "observation_width": self.observation_width,
        }

    def create_envs(
        self, n_envs: int, use_async_envs: bool = False
    ) -> dict[str, dict[str, gym.vector.VectorEnv]]:
        """``{category: {task: VectorEnv}}``: lerobot-eval reports per task and per category."""
        from ..tasks import get_task, task_names
        from .gym_env import ActiveArenaEnv

        if n_envs < 1:
            raise ValueError(f"n_envs must be >= 1, got {n_envs}")
        suites: dict[str, dict[str, gym.vector.VectorEnv]] = {}
        for name in task_names(self.task):
            fns = [partial(ActiveArenaEnv, **self.gym_kwargs, task=name) for _ in range(n_envs)]
            if use_async_envs and n_envs > 1:
                # LeRobot starts the workers from a fork server: with LeRobot and the env loaded there
                # once, a worker starts in a fraction of a second instead of importing them (~7 s)
                multiprocessing.set_forkserver_preload(["__main__", *FORKSERVER_PRELOAD])
                # LeRobot's own multi-task envs use this private class; no public route defers the
                # worker processes (and their GL contexts) to first use, so one task's run at a time
                # holds processes instead of every task's at once.
                from lerobot.envs.utils import _LazyAsyncVectorEnv

                vec = _LazyAsyncVectorEnv(fns)
            else:
                # A sub-env whose episode ended waits for the batch (no autoreset into an unplanned scene).
                vec = gym.vector.SyncVectorEnv([freeze_after_episode_end(fn) for fn in fns])
            suites.setdefault(get_task(name).category, {})[name] = vec
        return suites
