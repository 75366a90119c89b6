"""Gymnasium IDs for plain-gymnasium users: every registered task is

    gym.make("ActiveArena/<task>-v0", split="id" | "ood", fixed_view=False, render_mode="rgb_array")

with the task's step limit (``env.spec.max_episode_steps``), after ``import lerobot_activearena``
(which calls ``register_gym_envs``) or through gymnasium's ``"lerobot_activearena:ActiveArena/<task>-v0"``.
``reset(seed=s)`` plays scene seed ``s``; the evaluation protocol's manifest seeds are
``use_manifest=True`` (as ``lerobot-eval --env.type=activearena`` plays them).
"""

from __future__ import annotations

import gymnasium as gym

NAMESPACE = "ActiveArena"
ENTRY_POINT = "lerobot_activearena.envs.gym_env:ActiveArenaEnv"


def gym_id(task: str) -> str:
    return f"{NAMESPACE}/{task}-v0"


def register_gym_envs() -> list[str]:
    """Register ``ActiveArena/<task>-v0`` for every task of the registry (again: a no-op); returns the IDs."""
    from ..tasks.registry import get_task, task_names

    ids = []
    for name in task_names("all"):
        env_id = gym_id(name)
        if env_id not in gym.registry:
            gym.register(
                id=env_id,
                entry_point=ENTRY_POINT,
                max_episode_steps=get_task(name).max_episode_steps,
                kwargs={"task": name, "use_manifest": False},
            )
        ids.append(env_id)
    return ids
