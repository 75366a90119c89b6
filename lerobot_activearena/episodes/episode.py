"""The episode stepper: one simulated episode of a task, driven one action at a time by any policy
(the gym env, the scripted expert's episodes, the validity suite). Each step runs the physics,
checks its health, asks the success monitor, and updates the perception memory.

An episode ends at the first reported success or irreversible failure: a task failure (a wrong
button, an object off the table) or a physics blow-up (``failure_reason`` starts with
``physics:``). Stepping an ended episode moves the robot but changes no outcome.
"""

from __future__ import annotations

import numpy as np

from ..sim.action import ClipReport
from ..sim.health import PhysicsHealth
from ..sim.perception import PerceptionMemory
from ..sim.scene import HEAD_SIZE
from ..sim.simulator import ActiveArenaSim
from ..tasks.base import Task, TaskScene
from ..tasks.success import SuccessMonitor

FAILURE_STATES = ("DM", "CO", "CR")


def failure_state(success: bool, ever_seen: np.ndarray, visible_now: np.ndarray) -> str:
    """'' on success; DM: some task-relevant object never observed; CO: all observed but the final
    view does not cover them all; CR: the final view covers all and the task still failed."""
    if success:
        return ""
    if not ever_seen.all():
        return "DM"
    if not visible_now.all():
        return "CO"
    return "CR"


class Episode:
    def __init__(
        self,
        task: Task,
        scene: TaskScene,
        max_penetration: float | None = None,
        image_size: tuple[int, int] = HEAD_SIZE,
    ):
        """``max_penetration`` (m): a contact deeper than this also ends the episode as a physics
        failure (demonstrations must be clean); None: penetration is only tracked.
        ``image_size``: the head image's (height, width), 3:4 (``ActiveArenaSim``)."""
        self.task, self.scene = task, scene
        self.sim = ActiveArenaSim(scene.model, scene.info, *image_size)
        self.perception = PerceptionMemory(self.sim, len(scene.objects))
        self.monitor = SuccessMonitor(task, self.sim, scene)
        self.health = PhysicsHealth(self.sim.model, self.sim.data)
        self.max_penetration = max_penetration
        self.steps = 0
        self.success = False
        self.physics_problem: str | None = None
        self._observe()

    @property
    def failure_reason(self) -> str | None:
        if self.physics_problem:
            return f"physics: {self.physics_problem}"
        return self.monitor.failure_reason

    @property
    def done(self) -> bool:
        return self.success or self.failure_reason is not None

    def step(self, action) -> ClipReport:
        ended = self.done
        clip = self.sim.step(action)
        self.steps += 1
        if not ended:
            self.physics_problem = self.health.check()
            if self.physics_problem is None and self.max_penetration is not None:
                self.physics_problem = self.health.penetration_problem(self.max_penetration)
            if self.physics_problem is None:
                self.success = bool(self.monitor.update())
        self._observe()
        return clip

    def _observe(self) -> None:
        self.perception.observe()
        self.monitor.observe(self.perception.discovered)

    def failure_state(self) -> str:
        """DM / CO / CR of the episode so far ('' on success)."""
        t = self.scene.search_targets
        seen = np.append(self.perception.discovered[t], self.monitor.info_seen)
        return failure_state(self.success, seen, self.perception.visible[t])

    def unmet_checks(self) -> list[str]:
        return self.monitor.failed_checks

    def close(self) -> None:
        self.sim.close()
