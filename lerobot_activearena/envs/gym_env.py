"""Gymnasium environment of one ActiveArena task: head-camera pixels + 18-D state in, 18-D absolute
joint targets out, ``info["is_success"]`` every step, and the failure state (DM / CO / CR) when a
failed episode ends. An irreversible mistake (a wrong button, a task object off the table) ends the
episode at once: ``terminated=True``, ``is_success=False``, ``info["failure_reason"]``."""

from __future__ import annotations

import json
import os
from pathlib import Path

import gymnasium as gym
import numpy as np

from ..episodes.episode import Episode
from ..episodes.rollout import ExpertDriver
from ..sim import embodiment
from ..sim.action import ACTION_DIM, HEAD_PITCH, TORSO_YAW, validate_action
from ..sim.head_camera import validate_head_size
from ..sim.scene import CONTROL_HZ, HEAD_HEIGHT, HEAD_WIDTH
from ..sim.simulator import ActiveArenaSim
from ..tasks import get_task
from ..tasks.base import SPLITS
from ..tasks.sampling import sample_scene
from .manifests import DEFAULT_SEED_BASE, manifest_seed


class ActiveArenaEnv(gym.Env):
    metadata = {"render_modes": ["rgb_array"], "render_fps": CONTROL_HZ}

    def __init__(
        self,
        task: str = "click_bell_rotate_view",
        split: str = "id",
        fixed_view: bool = False,
        use_manifest: bool = True,
        seed_base: int = DEFAULT_SEED_BASE,
        expert_channel: bool = False,
        episode_log_dir: str | None = None,
        render_mode: str = "rgb_array",
        render_pixels: bool = True,
        max_episode_steps: int | None = None,
        observation_height: int = HEAD_HEIGHT,
        observation_width: int = HEAD_WIDTH,
    ):
        """``use_manifest``: reset(seed=s) plays the (s - seed_base)-th seed of the task's evaluation
        manifest (so lerobot-eval's seeds seed_base, seed_base+1, ... give the protocol's episodes in
        order whatever the batch size); otherwise ``s`` is the scene seed itself.
        ``expert_channel`` (privileged, off by default): the scripted expert runs alongside the
        episode and its next action is exposed as ``environment_state`` for the
        ``activearena_expert`` policy. Never enable it for learned policies or dataset recording.
        ``episode_log_dir``: append one JSON line per finished episode (seed, success, failure state,
        commanded torso/head targets) to ``<dir>/<task>_<split>_<pid>.jsonl`` for the report.
        ``render_pixels=False``: observations carry a black image (for policies that look at nothing,
        e.g. the validity suite's adversaries); visibility and failure states are still computed.
        ``max_episode_steps``: the step limit (default: the task's own, the protocol's).
        ``observation_height`` x ``observation_width``: the head image's size, 3:4 (default the
        paper's 384 x 512). The camera renders at that size (nothing is resized); visibility, the
        failure states and the success checks are the same at every 3:4 size."""
        if split not in SPLITS:
            raise ValueError(f"split must be one of {SPLITS}, got {split!r}")
        self.spec_task = get_task(task)
        self.task = task
        self.task_description = self.spec_task.instruction
        self.split, self.fixed_view, self.expert_channel = split, fixed_view, expert_channel
        self.episode_log_dir = episode_log_dir
        self.use_manifest, self.seed_base = use_manifest, seed_base
        self.render_mode = render_mode
        self.render_pixels = render_pixels
        self.image_size = validate_head_size(observation_height, observation_width)
        self._black = np.zeros((*self.image_size, 3), np.uint8)
        if max_episode_steps is not None and max_episode_steps < 1:
            raise ValueError(
                f"max_episode_steps must be >= 1 (or None for the task's limit), got {max_episode_steps}"
            )
        self._max_episode_steps = (
            max_episode_steps or self.spec_task.max_episode_steps
        )  # read by lerobot-eval
        self.episode: Episode | None = None
        spaces = {
            "pixels": gym.spaces.Dict({"head": gym.spaces.Box(0, 255, (*self.image_size, 3), np.uint8)}),
            "agent_pos": gym.spaces.Box(-np.inf, np.inf, (ACTION_DIM,), np.float32),
        }
        if expert_channel:
            spaces["environment_state"] = gym.spaces.Box(-np.inf, np.inf, (ACTION_DIM,), np.float32)
        self.observation_space = gym.spaces.Dict(spaces)
        low, high = joint_limits()
        self.action_space = gym.spaces.Box(low.astype(np.float32), high.astype(np.float32), dtype=np.float32)
        self._home = None

    # ---- gym API -------------------------------------------------------------------------------
    def reset(self, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        if seed is None:
            scene_seed = int(self.np_random.integers(0, 2**31 - 1))
        elif self.use_manifest:
            scene_seed = manifest_seed(self.task, self.split, int(seed) - self.seed_base)
        else:
            scene_seed = int(seed)
        if self.episode is not None:
            self.episode.close()
        self.episode = Episode(
            self.spec_task, sample_scene(self.spec_task, scene_seed, self.split), image_size=self.image_size
        )
        self.task_description = self.scene.instruction
        self._home = self.sim.home_action()
        self._episode_index = None if seed is None else int(seed) - self.seed_base
        self._scene_seed = scene_seed
        self._view_targets: list[list[float]] = []
        if self.expert_channel:
            self._start_expert()
        return self._obs(), {"is_success": False, "scene_seed": scene_seed}

    # the running episode's parts
    @property
    def sim(self) -> ActiveArenaSim | None:
        return None if self.episode is None else self.episode.sim

    @property
    def scene(self):
        return None if self.episode is None else self.episode.scene

    @property
    def monitor(self):
        return None if self.episode is None else self.episode.monitor

    def step(self, action):
        if self.episode is None:
            raise RuntimeError("call reset() before step()")
        action = validate_action(action)
        if self.fixed_view:  # ActiveArena-Fixed: head and torso stay at home whatever the policy says
            action = action.copy()
            action[TORSO_YAW], action[HEAD_PITCH] = embodiment.HOME_TORSO_YAW, embodiment.HOME_HEAD_PITCH
        ep = self.episode
        clip = ep.step(action)
        self._view_targets.append([float(action[TORSO_YAW]), float(action[HEAD_PITCH])])
        if self.expert_channel:
            self._advance_expert()
        success, terminated = ep.success, ep.done
        truncated = ep.steps >= self._max_episode_steps and not terminated
        info = {"is_success": success, "clipped_action": clip.as_dict()}
        if terminated or truncated:
            info["failure_state"] = ep.failure_state()
            info["failure_reason"] = ep.failure_reason or (
                ""
                if success
                else f"step limit {self._max_episode_steps} reached; unmet: {', '.join(ep.unmet_checks())}"
            )
            info["checks"] = dict(ep.monitor.checks)
            if self.episode_log_dir:
                self._log_episode(success, info["failure_state"], info["failure_reason"])
        return self._obs(), float(success), terminated, truncated, info

    def _log_episode(self, success: bool, failure: str, reason: str) -> None:
        d = Path(self.episode_log_dir)
        d.mkdir(parents=True, exist_ok=True)
        rec = {
            "task": self.task,
            "category": self.spec_task.category,
            "split": self.split,
            "fixed_view": self.fixed_view,
            "episode": self._episode_index,
            "scene_seed": self._scene_seed,
            "success": success,
            "failure_state": failure,
            "failure_reason": reason,
            "steps": self.episode.steps,
            "view_targets": self._view_targets,
        }
        with open(d / f"{self.task}_{self.split}_{os.getpid()}.jsonl", "a") as f:
            f.write(json.dumps(rec) + "\n")

    def render(self):
        return self.sim.render_head() if self.sim is not None else None

    def close(self):
        if self.episode is not None:
            self.episode.close()
            self.episode = None

    def _obs(self) -> dict:
        pixels = self.sim.render_head() if self.render_pixels else self._black
        obs = {"pixels": {"head": pixels}, "agent_pos": self.sim.state().astype(np.float32)}
        if self.expert_channel:
            obs["environment_state"] = self._expert_action.astype(np.float32)
        return obs

    # ---- privileged expert channel -------------------------------------------------------------
    @property
    def expert_gave_up(self) -> str | None:
        """Why the privileged expert gave up (object never found, grasp lost), else None. It then
        holds its last command until the episode ends."""
        driver = getattr(self, "_driver", None) if self.expert_channel else None
        return driver.failure if driver is not None and driver.finished else None

    def _start_expert(self) -> None:
        self._driver = ExpertDriver(
            self.spec_task, self.scene, self.sim, self.episode.perception, contain_errors=True
        )
        self._expert_action = self._driver.next_action()
        if self._expert_action is None:
            self._expert_action = self._home.copy()

    def _advance_expert(self) -> None:
        """The expert's next action from the current state; once its script ends (or it gives
        up: ``ExpertDriver.failure``), it holds its last command."""
        self._driver.observed()
        nxt = self._driver.next_action()
        if nxt is not None:
            self._expert_action = nxt


_LIMITS: tuple[np.ndarray, np.ndarray] | None = None


def joint_limits() -> tuple[np.ndarray, np.ndarray]:
    """18-D action bounds (joint limits; grippers 0..1) from an empty scene, computed once."""
    global _LIMITS
    if _LIMITS is None:
        from ..sim.scene import SceneBuilder

        model, info = SceneBuilder().compile()
        sim = ActiveArenaSim(model, info)
        _LIMITS = (sim.action_low.copy(), sim.action_high.copy())
        sim.close()
    return _LIMITS
