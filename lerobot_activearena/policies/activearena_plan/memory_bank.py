"""ActiveArena-Plan's executor memory: the executor (OFT) is prompted with the planner's subtask and sees
the retrieved frames of the uncapped stride-16 history and the current frame. At run time
(``MemoryBank``) each chunk's retrieval adds frames to a persistent, de-duplicated bank; a malformed
answer keeps the previous subtask and bank and is counted."""

from __future__ import annotations

from dataclasses import dataclass, field

from ...annotations.keyframes import STRIDE, planned_memory
from ..activearena_planner.answers import PlannerAnswer


def executor_memory(x: int, keyframes, stride: int = STRIDE) -> list[int]:
    """The executor's frames: those of the uncapped stride-16 history in a keyframe window, then the
    current frame ``x`` (not twice when it is the latest selected one)."""
    return [*planned_memory(x, keyframes, stride), x]


def executor_prompt(subtask: str) -> str:
    return (
        f'Your task is: "{subtask}" The input images are ordered from earliest to latest, and the last '
        "image is the current view. Please think about the next action."
    )


@dataclass
class MemoryBank:
    """One episode's planner-driven memory: the frames retrieved so far (absolute indices, sorted,
    unique), the current subtask, and how many planner answers were malformed."""

    subtask: str | None = None
    frames: list[int] = field(default_factory=list)
    malformed: int = 0

    def update(self, answer: PlannerAnswer | None, input_frames: list[int]) -> None:
        """Apply one planner answer to the images ``input_frames`` it saw (None: malformed, ignored)."""
        if answer is None:
            self.malformed += 1
            return
        self.subtask = answer.subtask
        self.frames = sorted(set(self.frames) | {input_frames[p] for p in answer.positions})

    def executor_frames(self, x: int) -> list[int]:
        """Retrieved frames before ``x``, then ``x``."""
        return [f for f in self.frames if f < x] + [x]
