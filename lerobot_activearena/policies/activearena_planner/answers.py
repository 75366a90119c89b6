"""ActiveArena-Plan's planner language (paper App. "ActiveArena-Plan Architecture"): the planner sees
the last <= K + 1 stride-16 frames and the instruction, and answers
``<think>..</think><subtask>..</subtask><retrieval>[positions]</retrieval>``; a position is a
retrieval target when its frame lies in [q, q + 16) for an earlier subtask keyframe q. Its prompt,
training target and the parser of its answers live here; the executor's memory is in
``activearena_plan.memory_bank``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ...annotations.keyframes import STRIDE, stride_sequence

PLANNER_HISTORY = 12  # K: history frames the planner sees (plus the current one)


def stride_frames(x: int, stride: int = STRIDE, history: int | None = PLANNER_HISTORY) -> list[int]:
    """The planner's input frames: x, x - s, x - 2s, ... >= 0 in chronological order; the last
    ``history`` + 1 of them (None: all)."""
    return stride_sequence(x, stride, history)


def planner_prompt(instruction: str) -> str:
    return (
        f'Your task is: "{instruction}" The input images are ordered from earliest to latest, and the last '
        "image is the current view. Please think about the current subtask and which frame(s) among the "
        "input images are worth remembering. Your response should be in the format of: "
        "<think>...</think><subtask>...</subtask><retrieval>...</retrieval>."
    )


def planner_target(n_frames: int, subtask: str, positions: list[int]) -> str:
    return (
        f'<think>Frames: {n_frames} total ({n_frames - 1} history + current). Now the subtask is "{subtask}"'
        f"</think><subtask>{subtask}</subtask><retrieval>[{', '.join(str(p) for p in positions)}]</retrieval>"
    )


@dataclass(frozen=True)
class PlannerAnswer:
    subtask: str
    positions: tuple[int, ...]


_ANSWER = re.compile(
    r"^\s*<think>.*?</think>\s*<subtask>(?P<subtask>.*?)</subtask>\s*"
    r"<retrieval>\s*\[(?P<positions>[\d,\s]*)\]\s*</retrieval>\s*$",
    re.DOTALL,
)


def parse_planner_answer(text: str, n_frames: int) -> PlannerAnswer | None:
    """The subtask and retrieval positions of a planner answer, or None when it is malformed: the
    wrong structure, not exactly one non-empty subtask, or a position outside the input images."""
    m = _ANSWER.match(text)
    if m is None or text.count("<subtask>") != 1:
        return None
    subtask = m["subtask"].strip()
    items = [p.strip() for p in m["positions"].split(",")] if m["positions"].strip() else []
    if not subtask or any(not p.isdigit() for p in items):
        return None
    positions = tuple(sorted({int(p) for p in items}))
    if positions and positions[-1] >= n_frames:
        return None
    return PlannerAnswer(subtask, positions)
