"""Gymnasium environment over the simulator: head-camera pixels + 18-D state in, 18-D joint
targets out, ``info["is_success"]`` every step."""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from ..sim import action as A
from ..sim.scene import CONTROL_HZ, HEAD_HEIGHT, HEAD_WIDTH
from ..sim.simulator import ActiveArenaSim
from .reference_task import TASKS


class ActiveArenaEnv(gym.Env):
    metadata = {"render_modes": ["rgb_array"], "render_fps": CONTROL_HZ}

    def __init__(self, task: str = "reference_pick_can", render_mode: str = "rgb_array"):
        if task not in TASKS:
            raise ValueError(f"unknown ActiveArena task {task!r}; available: {sorted(TASKS)}")
        self.task = TASKS[task]()
        self.task_description = self.task.instruction
        self.render_mode = render_mode
        self._max_episode_steps = self.task.max_episode_steps
        # A scene of seed 0 until the first reset: it gives the action limits (it renders nothing yet).
        self.sim: ActiveArenaSim | None = ActiveArenaSim(*self.task.build(0))
        self._was_reset = False
        self.observation_space = gym.spaces.Dict({
            "pixels": gym.spaces.Dict({"head": gym.spaces.Box(0, 255, (HEAD_HEIGHT, HEAD_WIDTH, 3), np.uint8)}),
            "agent_pos": gym.spaces.Box(-np.inf, np.inf, (A.ACTION_DIM,), np.float32),
        })
        self.action_space = gym.spaces.Box(self.sim.action_low.astype(np.float32), self.sim.action_high.astype(np.float32),
                                           dtype=np.float32)

    def _obs(self) -> dict:
        return {"pixels": {"head": self.sim.render_head()}, "agent_pos": self.sim.state().astype(np.float32)}

    def reset(self, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        scene_seed = int(self.np_random.integers(0, 2**31 - 1)) if seed is None else int(seed)
        if self.sim is not None:
            self.sim.close()
        model, info = self.task.build(scene_seed)
        self.sim = ActiveArenaSim(model, info)
        self.task.on_reset(self.sim)
        self._was_reset = True
        return self._obs(), {"is_success": False, "seed": scene_seed}

    def step(self, action):
        if not self._was_reset or self.sim is None:
            raise RuntimeError("call reset() before step()")
        clip = self.sim.step(action)
        success = self.task.is_success(self.sim)
        info = {"is_success": success, "clipped_action": clip.as_dict()}
        return self._obs(), float(success), success, False, info

    def render(self):
        return self.sim.render_head() if self.sim is not None else None

    def close(self):
        if self.sim is not None:
            self.sim.close()
            self.sim = None
            self._was_reset = False
