"""What a task is: name, category, instruction, subtasks, scene layout, success and expert script."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, ClassVar

import mujoco
import numpy as np

if TYPE_CHECKING:
    from ..expert.context import ExpertContext
    from ..sim.scene import SceneInfo
    from ..sim.simulator import ActiveArenaSim
    from .sampling import SceneDraft

CATEGORIES = {
    "SS": "single-target search",
    "SL": "search and localize",
    "ML": "multi-target localization",
    "MD": "memory-dependent decision",
    "IA": "interactive acquisition",
}
SPLITS = ("id", "ood")


@dataclass(frozen=True)
class Subtask:
    id: int  # semantic subtask id (T1 -> 1)
    name: str
    text: str
    instruction_idx: int  # index into the task's distinct subtask instructions (T1/T4 can share one)


@dataclass
class TaskScene:
    """A sampled, validated scene of one task: the compiled model plus the episode's parameters."""

    task: str
    seed: int
    split: str
    attempt: int
    model: mujoco.MjModel
    info: SceneInfo
    objects: list[str]  # registered task objects; position = object index in every mask
    labels: list[str]  # human-readable names, same order
    params: dict = field(default_factory=dict)
    instruction: str = ""
    search_targets: list[int] = field(default_factory=list)


class SuccessMonitor:
    """Tracks success over an episode. The default checks the task's state predicate every step;
    tasks with events (presses) latch them here."""

    def __init__(self, task: Task, sim: ActiveArenaSim, scene: TaskScene):
        self.task, self.sim, self.scene = task, sim, scene
        self.success = False

    def update(self) -> bool:
        self.success = bool(self.task.is_success(self.sim, self.scene))
        return self.success


class Task:
    name: ClassVar[str]
    category: ClassVar[str]
    instruction: ClassVar[str]
    subtasks: ClassVar[tuple[Subtask, ...]]
    max_episode_steps: ClassVar[int] = 600

    def layout(self, draft: SceneDraft) -> None:
        """Place the registered task objects (and set ``draft.params``)."""
        raise NotImplementedError

    def instruction_for(self, params: dict) -> str:
        return self.instruction

    def search_targets(self, scene: TaskScene) -> list[int]:
        """Objects whose observation the task needs (design-principle checks, DM/CO/CR)."""
        return list(range(len(scene.objects)))

    def reach_targets(self, scene: TaskScene) -> dict[int, tuple[str, ...]]:
        """Objects the arms must touch, with the arms allowed to (principle check: reachable)."""
        return {}

    def information_hidden_at_start(self, scene: TaskScene) -> bool:
        """True when the deciding information is hidden at reset by construction (e.g. a colour on
        an object's back face); then principle (1) does not need an unseen object."""
        return False

    def is_success(self, sim: ActiveArenaSim, scene: TaskScene) -> bool:
        raise NotImplementedError

    def monitor(self, sim: ActiveArenaSim, scene: TaskScene) -> SuccessMonitor:
        return SuccessMonitor(self, sim, scene)

    def expert(self, ctx: ExpertContext, scene: TaskScene) -> Iterator[np.ndarray]:
        raise NotImplementedError

    def subtask(self, sid: int) -> Subtask:
        for s in self.subtasks:
            if s.id == sid:
                return s
        raise KeyError(f"{self.name} has no subtask {sid}")


TASKS: dict[str, type[Task]] = {}


def register_task(cls: type[Task]) -> type[Task]:
    if cls.name in TASKS:
        raise ValueError(f"task {cls.name!r} registered twice")
    if cls.category not in CATEGORIES:
        raise ValueError(f"task {cls.name!r}: unknown category {cls.category!r}; use one of {sorted(CATEGORIES)}")
    TASKS[cls.name] = cls
    return cls
