"""What a task is: its row of the paper's inventory table (name, category, instruction, subtasks,
step limit), a layout by region, named success checks, irreversible failures and an expert script.

A task module (``tasks/inventory/<paper name>.py``) subclasses ``Task``; defining the class
registers it. See ``tasks/inventory/click_bell_rotate_view.py`` for a commented example.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, ClassVar

import mujoco
import numpy as np

from ..sim.workspace import WORKSPACES

if TYPE_CHECKING:
    from ..expert.context import ExpertContext
    from ..sim.scene import SceneInfo
    from ..sim.simulator import ActiveArenaSim
    from .draft import SceneDraft
    from .success import SuccessMonitor

CATEGORIES = {
    "SS": "single-object search",
    "SL": "single-object loop",
    "ML": "multi-object loop",
    "MD": "multi-object decision",
    "IA": "interactive information acquisition",
}
SPLITS = ("id", "ood")


@dataclass(frozen=True)
class Subtask:
    id: int  # semantic subtask id (T1 -> 1), the position in the task's declaration
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
    hidden: list[str] = field(default_factory=list)  # placed out of the home view
    reach: dict[str, tuple[str, ...]] = field(default_factory=dict)  # object -> arms that may touch it

    def obj(self, name: str):
        return self.info.objects[self.objects.index(name)]


class Task:
    name: ClassVar[str]
    category: ClassVar[str]
    instruction: ClassVar[str]  # the paper's sentence (one instance of a template)
    # A sentence with ``{field}``s the episode fills from ``scene.params`` (the mat's colour, the
    # object's name, the arm), and the values each field takes; None: the sentence is fixed.
    instruction_template: ClassVar[str | None] = None
    instruction_values: ClassVar[dict[str, tuple[str, ...]]] = {}
    subtasks: ClassVar[tuple[Subtask, ...]]
    max_episode_steps: ClassVar[int]  # the protocol's evaluation step limit (paper's release)
    # "fan" (one level) or "two_level" (the lower fan plus the upper band on its column): the
    # sampler builds it, and placement, clutter, the search views and the checks follow it.
    workspace: ClassVar[str] = "fan"

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "name" in cls.__dict__:
            check_instruction_template(cls)
            register_task(cls)

    # ---- scene -------------------------------------------------------------------------------
    def layout(self, draft: SceneDraft) -> None:
        """Place the registered task objects (and set ``draft.params``)."""
        raise NotImplementedError

    def instruction_for(self, params: dict) -> str:
        """The episode's instruction: the template filled from ``params`` (the sampler's
        ``draft.params``), or the fixed sentence."""
        if self.instruction_template is None:
            return self.instruction
        values = {}
        for key, allowed in self.instruction_values.items():
            if key not in params:
                raise KeyError(f"{self.name}: the layout did not set params[{key!r}] for its instruction")
            if params[key] not in allowed:
                raise ValueError(f"{self.name}: params[{key!r}] = {params[key]!r} is not one of {allowed}")
            values[key] = params[key]
        return self.instruction_template.format(**values)

    @classmethod
    def instruction_texts(cls) -> list[str]:
        """The sentence, and every value a template field takes (a tokenizer's corpus)."""
        return [cls.instruction, *(v for vals in cls.instruction_values.values() for v in vals)]

    def search_targets(self, scene: TaskScene) -> list[int]:
        """Objects whose observation the task needs (design-principle checks, DM/CO/CR)."""
        return list(range(len(scene.objects)))

    def information_faces(self, scene: TaskScene) -> list[str]:
        """Objects whose hidden information face (``functional.info_face``: a back patch, a date label)
        the task needs read. Each must face away from the camera at reset and be seen before success."""
        return []

    def information_hidden_at_start(self, scene: TaskScene) -> bool:
        """True when the deciding information is hidden at reset by construction (every information
        face turned away from the home view); then principle (1) does not need an unseen object."""
        faces = self.information_faces(scene)
        if not faces:
            return False
        from ..sim.head_camera import hidden_face_visible

        data = mujoco.MjData(scene.model)
        mujoco.mj_forward(scene.model, data)
        return not any(hidden_face_visible(scene.model, data, scene.obj(n)) for n in faces)

    # ---- success -----------------------------------------------------------------------------
    def evaluate(self, sim: ActiveArenaSim, scene: TaskScene, monitor: SuccessMonitor) -> dict[str, bool]:
        """Named sub-conditions of success; success = all hold for ``STABLE_FRAMES`` frames."""
        raise NotImplementedError

    def failure(self, sim: ActiveArenaSim, scene: TaskScene, monitor: SuccessMonitor) -> str | None:
        """An irreversible mistake that ends the episode as a failure (reason), else None."""
        return None

    # ---- expert ------------------------------------------------------------------------------
    def expert(self, ctx: ExpertContext, scene: TaskScene) -> Iterator[np.ndarray]:
        raise NotImplementedError

    def subtask(self, sid: int) -> Subtask:
        for s in self.subtasks:
            if s.id == sid:
                return s
        raise KeyError(f"{self.name} has no subtask {sid}")


TASKS: dict[str, type[Task]] = {}


def register_task(cls: type[Task]) -> type[Task]:
    if cls.name in TASKS and TASKS[cls.name] is not cls:
        raise ValueError(
            f"task {cls.name!r} registered twice ({TASKS[cls.name].__module__} and {cls.__module__})"
        )
    if cls.category not in CATEGORIES:
        raise ValueError(
            f"task {cls.name!r}: unknown category {cls.category!r}; use one of {sorted(CATEGORIES)}"
        )
    if cls.workspace not in WORKSPACES:
        raise ValueError(
            f"task {cls.name!r}: unknown workspace {cls.workspace!r}; use one of {sorted(WORKSPACES)}"
        )
    ids = [s.id for s in cls.subtasks]
    if ids != list(range(1, len(ids) + 1)):
        raise ValueError(f"task {cls.name!r}: subtask ids must be 1..n in declaration order, got {ids}")
    TASKS[cls.name] = cls
    return cls


def check_instruction_template(cls) -> None:
    """A template's fields are exactly ``instruction_values``' keys, and the paper's sentence is one
    of its instances (so the template says what the paper says)."""
    template = cls.instruction_template
    if template is None:
        return
    fields = set(re.findall(r"{(\w+)}", template))
    if fields != set(cls.instruction_values):
        raise TypeError(
            f"{cls.__name__}: instruction_template fields {sorted(fields)} differ from "
            f"instruction_values {sorted(cls.instruction_values)}"
        )
    pattern = re.escape(template)
    for key, vals in cls.instruction_values.items():
        pattern = pattern.replace(re.escape("{" + key + "}"), "(?:" + "|".join(map(re.escape, vals)) + ")")
    if not re.fullmatch(pattern, cls.instruction):
        raise TypeError(
            f"{cls.__name__}: the paper's instruction {cls.instruction!r} is not an instance of "
            f"the template {template!r} with the values {cls.instruction_values}"
        )
