"""ActiveArena as a benchmark of allenai's vla-eval harness (``pip install vla-eval==0.8.0``, the
``vla-eval`` extra).

Each vla-eval task is one task x split pair of the protocol; episode k of a pair plays the k-th seed
of that pair's evaluation manifest (``lerobot_activearena.envs.manifests``), so the same
``episodes_per_task`` gives the same episodes as ``activearena-eval``. The env is the gymnasium one,
``ActiveArena/<task>-v0``, with the task's own step limit.

Wire format (vla-eval's recommended keys):

* observation: ``images["head"]`` (uint8 H x W x 3, the head camera), ``state`` (float32 18-D: left
  arm 7, left gripper, right arm 7, right gripper, torso yaw, head pitch) and ``task_description``
  (the episode's instruction);
* action: ``actions``, 18 absolute joint targets in the state's layout (the first row of a chunk).

Per-episode metrics: ``success``; ``failure_state`` (DM / CO / CR, "" on success) and
``failure_reason``; ``failure_DM`` / ``failure_CO`` / ``failure_CR`` (0/1, averaged by vla-eval
into ``mean_failure_DM`` ...); ``scene_seed``. vla-eval adds ``steps`` per episode.

Run it (model server first, then the harness, in this venv; see ``docs/remote.md``)::

    .venv/bin/python -m vla_eval.model_servers.behavior1k_baseline \\
        --address 127.0.0.1:8000 --args.action_dim 18 &
    .venv/bin/vla-eval run --no-docker -c configs/vla_eval/activearena.yaml
"""

from __future__ import annotations

import sys
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from vla_eval.benchmarks.base import StepBenchmark, StepResult
from vla_eval.recording import NullEpisodeRecorder
from vla_eval.render import configure_mujoco_render
from vla_eval.specs import IMAGE_RGB, LANGUAGE, DimSpec
from vla_eval.types import Action, EpisodeResult, Observation, Task

import lerobot_activearena  # noqa: F401  (selects the GL backend, registers the gym IDs; no MuJoCo yet)
from lerobot_activearena.envs.gym_ids import STEP_LIMITS, gym_id
from lerobot_activearena.envs.manifests import MANIFEST_SIZE, manifest_seed

ACTION_DIM = 18
FAILURE_STATES = ("DM", "CO", "CR")


def _as_list(value: str | list[str]) -> list[str]:
    return [p.strip() for p in (value.split(",") if isinstance(value, str) else value) if p.strip()]


class ActiveArenaBenchmark(StepBenchmark):
    """ActiveArena's task x split pairs; episode k plays manifest seed k."""

    render_backends: ClassVar[frozenset[str]] = frozenset({"gpu", "cpu"})
    _ALL_RECORD_FIELDS = frozenset({"reward", "done", "success"})

    @classmethod
    def configure_render(cls, mode: str) -> dict[str, str]:
        """cpu: OSMesa; gpu: the backend ``lerobot_activearena`` picks (MUJOCO_GL, else EGL)."""
        if mode == "cpu" and "mujoco" in sys.modules:
            raise RuntimeError("render: cpu requested after mujoco was imported; its GL backend is bound")
        return configure_mujoco_render(mode)

    def __init__(
        self,
        tasks: str | list[str] = "all",
        splits: str | list[str] = "id,ood",
        observation_height: int = 384,
        observation_width: int = 512,
        send_state: bool = True,
    ) -> None:
        """``tasks``: "all", a category (SS/SL/ML/MD/IA), task names, or a comma list of those;
        ``splits``: "id", "ood" or both; the head image is ``observation_height`` x
        ``observation_width`` (3:4); ``send_state=False`` leaves the state out of the observation."""
        super().__init__()
        from lerobot_activearena.tasks import get_task, task_names  # imports MuJoCo: after configure_render
        from lerobot_activearena.tasks.base import SPLITS

        if unknown := [s for s in _as_list(splits) if s not in SPLITS]:
            raise ValueError(f"splits must be among {SPLITS}, got {unknown}")
        self._tasks: list[Task] = [
            {"name": f"{name}_{split}", "task": name, "split": split, "suite": get_task(name).category}
            for name in task_names(",".join(_as_list(tasks)))
            for split in _as_list(splits)
        ]
        self._size = (int(observation_height), int(observation_width))
        self._send_state = send_state
        self._env: gym.Env | None = None
        self._env_key: tuple[str, str] | None = None
        self._recorder = NullEpisodeRecorder()  # start_episode replaces it; reset() works without
        self._scene_seed = -1

    # ---- vla-eval's StepBenchmark ------------------------------------------------------------
    def get_tasks(self) -> list[Task]:
        return list(self._tasks)

    def reset(self, task: Task) -> Any:
        key = (task["task"], task["split"])
        if self._env_key != key:
            self.cleanup()
            self._env = gym.make(
                gym_id(task["task"]),
                split=task["split"],
                render_mode="rgb_array",
                observation_height=self._size[0],
                observation_width=self._size[1],
                use_manifest=False,  # reset(seed=s) plays scene seed s: the manifest's, below
            )
            self._env_key = key
        self._scene_seed = manifest_seed(task["task"], task["split"], int(task.get("episode_idx", 0)))
        obs, _ = self._env.reset(seed=self._scene_seed)
        self._recorder.record_video(obs["pixels"]["head"])
        return obs

    def step(self, action: Action) -> StepResult:
        target = np.asarray(action.get("actions", action.get("action")), dtype=np.float32)
        if target.size == 0 or target.size % ACTION_DIM:
            raise ValueError(f"ActiveArena takes {ACTION_DIM}-D joint targets, got shape {target.shape}")
        obs, reward, terminated, truncated, info = self._env.step(target.reshape(-1, ACTION_DIM)[0])
        done = bool(terminated or truncated)
        self._recorder.record_video(obs["pixels"]["head"])
        self._recorder.record_step(reward=float(reward), done=done, success=bool(info["is_success"]))
        return StepResult(obs=obs, reward=float(reward), done=done, info=info)

    def make_obs(self, raw_obs: Any, task: Task) -> Observation:
        obs: Observation = {
            "images": {"head": raw_obs["pixels"]["head"]},
            "task_description": self._env.unwrapped.task_description,
        }
        if self._send_state:
            obs["state"] = raw_obs["agent_pos"]
        return obs

    def get_step_result(self, step_result: StepResult) -> EpisodeResult:
        info, episode = step_result.info, self._env.unwrapped.episode
        success = bool(info.get("is_success", False))
        state = info.get("failure_state")
        reason = info.get("failure_reason")
        if state is None:  # vla-eval's max_steps ended the episode before the task's step limit
            state = episode.failure_state()
            reason = "" if success else f"stopped by vla-eval's max_steps after {episode.steps} steps"
        result: EpisodeResult = {
            "success": success,
            "failure_state": state,
            "failure_reason": reason,
            "scene_seed": self._scene_seed,
        }
        result.update({f"failure_{s}": int(state == s) for s in FAILURE_STATES})
        return result

    # ---- metadata ----------------------------------------------------------------------------
    def get_metric_keys(self) -> dict[str, str]:
        return {"success": "mean", **{f"failure_{s}": "mean" for s in FAILURE_STATES}}

    def get_metadata(self) -> dict[str, Any]:
        # the runner's cap: the longest selected task's limit; each env ends at its own task's
        return {
            "max_steps": max(STEP_LIMITS[t["task"]] for t in self._tasks),
            "max_episodes_per_task": MANIFEST_SIZE,
        }

    def get_action_spec(self) -> dict[str, DimSpec]:
        return {"joints": DimSpec("joints", ACTION_DIM, "activearena_absolute_joint_targets")}

    def get_observation_spec(self) -> dict[str, DimSpec]:
        spec = {"head": IMAGE_RGB, "language": LANGUAGE}
        if self._send_state:
            spec["state"] = DimSpec("state", ACTION_DIM, "activearena_joint_positions")
        return spec

    def cleanup(self) -> None:
        if self._env is not None:
            self._env.close()
        self._env, self._env_key = None, None
