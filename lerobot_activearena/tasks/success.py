"""Success and failure over an episode.

Every step the monitor asks the task for its named checks (``Task.evaluate``) and for an irreversible
mistake (``Task.failure``). Success is reported once every check has held for ``STABLE_FRAMES``
consecutive frames (state goals must hold with the robot off the objects). Events (a press, a
switch) latch through ``monitor.event(name, happened_now)``: the task decides what makes the event
count (instructed arm, instructed part, object upright and in place) at the frame it happens.

Every task also needs ``saw_task_objects``: the head camera has seen every task-relevant object
(and, for information-acquisition tasks, the hidden information) before an event counts and before
success is reported. A policy that acts without ever looking (flailing, a memorised motion) is in
the DM failure state by the paper's definition; it cannot succeed by luck.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..sim.head_camera import hidden_face_visible
from . import predicates

if TYPE_CHECKING:
    from ..sim.simulator import ActiveArenaSim
    from .base import Task, TaskScene

STABLE_FRAMES = 8


class SuccessMonitor:
    def __init__(self, task: Task, sim: ActiveArenaSim, scene: TaskScene):
        self.task, self.sim, self.scene = task, sim, scene
        self.events: dict[str, bool] = {}
        self.checks: dict[str, bool] = {}
        self.streak = 0
        self.success = False
        self.failure_reason: str | None = None
        self.state: dict = {}  # per-episode memory a task's checks may keep (e.g. a motion history)
        self._faces = {n: scene.obj(n) for n in task.information_faces(scene)}
        self.faces_seen: set[str] = set()  # information faces the head camera has seen
        self.info_seen = not self._faces  # every hidden information face was seen
        self.informed = False  # every task-relevant object and the information were seen
        self._free_objects = [n for n in scene.objects if predicates.is_free(sim, n)]

    def observe(self, discovered: np.ndarray) -> None:
        """After each observation: ``discovered`` = registered objects the head camera has seen so far."""
        if not self.info_seen:
            model, data = self.sim.model, self.sim.data
            self.faces_seen |= {
                n
                for n, o in self._faces.items()
                if n not in self.faces_seen and hidden_face_visible(model, data, o)
            }
            self.info_seen = len(self.faces_seen) == len(self._faces)
        self.informed = bool(np.asarray(discovered)[self.scene.search_targets].all()) and self.info_seen

    def event(self, name: str, happened_now: bool) -> bool:
        """Latch ``name`` the first frame it happens after the task-relevant objects were seen."""
        self.events[name] = self.events.get(name, False) or (bool(happened_now) and self.informed)
        return self.events[name]

    def update(self) -> bool:
        """Evaluate the current frame; returns whether success is reported."""
        if self.success or self.failure_reason:
            return self.success
        checks = self.task.evaluate(self.sim, self.scene, self)
        if not checks:
            raise ValueError(f"{self.task.name}.evaluate() returned no checks")
        self.checks = {"saw_task_objects": self.informed, **{k: bool(v) for k, v in checks.items()}}
        self.failure_reason = self.task.failure(self.sim, self.scene, self) or self._object_off_table()
        if self.failure_reason:
            return False
        self.streak = self.streak + 1 if all(self.checks.values()) else 0
        self.success = self.streak >= STABLE_FRAMES
        return self.success

    def _object_off_table(self) -> str | None:
        """Every task: a free task object that left the table ends the episode."""
        for name in self._free_objects:
            if predicates.off_table(self.sim, name):
                return f"{name} fell off the table"
        return None

    @property
    def failed_checks(self) -> list[str]:
        return [k for k, v in self.checks.items() if not v]
