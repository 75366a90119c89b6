"""Handover rollouts: the scripted expert plays an episode up to a handover point, then a policy
finishes it. The policy sees every observation from the first step (its actions are discarded until
the handover), so its memory bank holds what it would hold had it acted as the expert did. Where the
success rate jumps as the handover moves later is the part of the task the policy cannot do
(``analysis/policies/handover_eval.py``)."""

from __future__ import annotations

import re
from collections.abc import Callable

import numpy as np
import torch


def handover_step(point: str, subtasks: list[int]) -> int:
    """The env step at which the policy takes over, from the expert's per-frame subtasks."""
    if point == "start":
        return 0
    if point == "never":
        return 10**9
    m = re.fullmatch(r"subtask:(\d+)(?:\+(\d+))?", point)
    if m is None:
        raise ValueError(f"handover point {point!r}: use start, never, subtask:K or subtask:K+N")
    k, extra = int(m.group(1)), int(m.group(2) or 0)
    if k not in subtasks:
        raise ValueError(f"the expert's episode has no subtask {k} (it has {sorted(set(subtasks))})")
    return subtasks.index(k) + extra


def torso_offset(rad: float, from_step: int = 8) -> Callable[[int, np.ndarray], np.ndarray]:
    """An ``adjust_expert`` that adds ``rad`` to the expert's torso yaw from ``from_step`` on (the
    expert's first turn is done by step 8): the policy takes over from a heading off the expert's."""
    from ..sim.action import TORSO_YAW

    def adjust(t: int, actions: np.ndarray) -> np.ndarray:
        if t >= from_step:
            actions[:, TORSO_YAW] += rad
        return actions

    return adjust


def play_with_handover(
    policy,
    processors,
    vec,
    seed: int,
    handover: int,
    render_callback=None,
    adjust_expert: Callable[[int, np.ndarray], np.ndarray] | None = None,
    replan: bool = False,
) -> None:
    """One episode through LeRobot's rollout loop on ``vec`` (one env with ``expert_channel``), the
    expert's action executed before step ``handover``; ``render_callback(vec)`` after every step.
    ``adjust_expert(t, actions)``: what runs instead of the expert's (1, 18) actions at step t (e.g. the
    torso turned off its heading: where the policy takes over from). ``replan``: the policy decides a new
    chunk at the handover; otherwise a handover between its decisions (every ``n_action_steps`` steps)
    first plays the rest of the chunk it decided before the handover, from where the expert had the
    robot then."""
    from lerobot.scripts import lerobot_eval

    real_reset, real_step = vec.reset, vec.step
    state = {"t": 0, "expert": None}

    def reset(**kwargs):
        obs, info = real_reset(**kwargs)
        state.update(t=0, expert=obs["environment_state"].copy())
        return obs, info

    def step(actions):
        if state["t"] < handover:
            actions = state["expert"].astype(actions.dtype)
            if adjust_expert is not None:
                actions = adjust_expert(state["t"], actions.copy())
        out = real_step(actions)
        state.update(t=state["t"] + 1, expert=out[0]["environment_state"].copy())
        if replan and state["t"] == handover:
            policy.replan()
        return out

    vec.reset, vec.step = reset, step
    try:
        with torch.no_grad():
            lerobot_eval.rollout(vec, policy, *processors, seeds=[seed], render_callback=render_callback)
    finally:
        del vec.reset, vec.step
