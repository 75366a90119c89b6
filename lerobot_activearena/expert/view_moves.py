"""Camera moves of the expert (paper App. "New Action Primitives"): generators of 18-D actions that
turn the head and torso only, never in a step with an arm move. ``move_head``, ``move_torso[_to]``,
``move_head_torso_to`` (trapezoidal profiles under the joint limits), ``look_at`` (a world point) and
``look_at_object`` (where it was last seen), ``face_for_arm`` (the torso turns so the object sits in
front of the chosen arm), ``search`` (a sector sweep that remembers explored sectors; stops when the
target appears, then centres it) and ``sweep_all``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator

import numpy as np

from ..annotations.schema import (
    CAMERA_CENTER,
    CAMERA_HOLD,
    CAMERA_SEARCH,
    STAGE_ANCHOR,
    STAGE_SEARCH,
)
from ..sim import embodiment
from ..sim.action import HEAD_PITCH, TORSO_YAW
from ..sim.head_camera import SEARCH_PITCH
from .context import ExpertContext, ExpertError
from .kinematics import torso_yaw_for_arm
from .motion import Actions, hold, trapezoid

TORSO_VMAX, TORSO_AMAX = embodiment.TORSO_LIMITS  # the paper's 2.5 rad/s, 10 rad/s^2


HEAD_VMAX, HEAD_AMAX = embodiment.HEAD_LIMITS  # the paper's 10 rad/s, 25 rad/s^2


def move_head_torso_to(
    ctx: ExpertContext,
    yaw: float,
    pitch: float,
    mode: int,
    stop_when: Callable[[], bool] | None = None,
    settle_after: bool = True,
) -> Iterator[np.ndarray]:
    """Turn torso and head together to (yaw, pitch); returns True if ``stop_when`` fired. Unless it
    fired or ``settle_after`` is False, hold the command until the drives have caught up."""
    y0, p0 = ctx.yaw, ctx.pitch
    yaw = float(np.clip(yaw, *embodiment.TORSO_YAW_RANGE))
    pitch = float(np.clip(pitch, *embodiment.HEAD_PITCH_RANGE))
    sy = trapezoid(yaw - y0, TORSO_VMAX, TORSO_AMAX)
    sp = trapezoid(pitch - p0, HEAD_VMAX, HEAD_AMAX)
    s = sy if len(sy) >= len(sp) else sp
    ctx.intent.camera_mode = mode
    ctx.intent.camera_target_theta = 90.0 + math.degrees(yaw)
    fired = False
    for sk in s:
        ctx.action[TORSO_YAW] = y0 + sk * (yaw - y0)
        ctx.action[HEAD_PITCH] = p0 + sk * (pitch - p0)
        yield ctx.emit()
        if stop_when is not None and stop_when():
            fired = True
            break
    ctx.intent.camera_mode = CAMERA_HOLD
    ctx.intent.camera_target_theta = math.nan
    if not fired and settle_after:
        yield from settle(ctx)
    return fired


def settle(ctx: ExpertContext, tol: float = 0.015, max_steps: int = 12) -> Actions:
    """Hold the command until torso and head have caught up with it (the drives lag the profile)."""
    for _ in range(max_steps):
        err = np.abs(ctx.sim.state()[[TORSO_YAW, HEAD_PITCH]] - ctx.action[[TORSO_YAW, HEAD_PITCH]])
        if err.max() < tol:
            return
        yield ctx.emit()


def move_head(ctx: ExpertContext, delta: float, mode: int = CAMERA_CENTER) -> Actions:
    """Relative head pitch."""
    yield from move_head_torso_to(ctx, ctx.yaw, ctx.pitch + delta, mode)


def move_torso_to(ctx: ExpertContext, yaw: float, mode: int = CAMERA_CENTER) -> Actions:
    """Absolute torso yaw (head holds)."""
    yield from move_head_torso_to(ctx, yaw, ctx.pitch, mode)


def move_torso(ctx: ExpertContext, delta: float, mode: int = CAMERA_CENTER) -> Actions:
    """Relative torso yaw."""
    yield from move_head_torso_to(ctx, ctx.yaw + delta, ctx.pitch, mode)


def look_at_object(ctx: ExpertContext, i: int, mode: int = CAMERA_CENTER) -> Actions:
    """Centre object ``i`` where the expert last saw it (never where it is unseen)."""
    if i not in ctx.memory:
        raise ExpertError(f"{ctx.objects[i]} has not been seen yet; search for it first")
    yield from look_at(ctx, ctx.memory[i], mode)


def look_at(ctx: ExpertContext, point, mode: int = CAMERA_CENTER) -> Actions:
    yaw, pitch = ctx.gaze.aim(point, ctx.yaw, ctx.pitch)
    yield from move_head_torso_to(ctx, yaw, pitch, mode)


def face_for_arm(ctx: ExpertContext, point, side: str) -> Actions:
    """Torso turns so ``point`` is in front of ``side``'s arm (off by ``ctx.face_offset()``: 0 but
    in off-centre demonstrations); the head pitches to keep it in view."""
    low, high = embodiment.TORSO_YAW_RANGE
    yaw = float(np.clip(torso_yaw_for_arm(point, side) + ctx.face_offset(), low, high))
    _, pitch = ctx.gaze.aim(point, yaw, ctx.pitch, fix_yaw=True)
    yield from move_head_torso_to(ctx, yaw, pitch, CAMERA_CENTER)


def search(ctx: ExpertContext, i: int, center: bool = True) -> Actions:
    """Find object ``i``: if it was seen before, turn to where it was; else sweep unexplored sectors
    nearest-first (explored ones last), stop as soon as it is visible, then centre it. With
    ``ctx.decision_period`` N > 1 "as soon as" means at the next frame that is a multiple of N, and a
    sector is declared empty there too: what the expert does in each N-frame chunk follows from the
    view at the chunk's first frame, as for a policy that executes N-action chunks."""
    it = ctx.intent
    it.focus, it.stage, it.info_complete = i, STAGE_SEARCH, False
    it.search_targets = it.search_targets | {i}
    if i not in ctx.memory:

        def seen() -> bool:  # a decision frame where the camera shows it
            return ctx.deciding() and bool(ctx.perception.visible[i])

        views = ctx.views  # lower sectors first, then (two-level) the upper ones
        order = sorted(
            range(len(views)),
            key=lambda s: (s in ctx.explored, views[s][1] != SEARCH_PITCH, abs(views[s][0] - ctx.yaw)),
        )
        chunked = ctx.decision_period > 1  # the drives settle while it waits for its decision frame
        for s in order:
            there = math.isclose(ctx.yaw, views[s][0]) and math.isclose(ctx.pitch, views[s][1])
            if not (chunked and there):  # (a move to where it is would still take a frame)
                yield from move_head_torso_to(
                    ctx, *views[s], CAMERA_SEARCH, stop_when=seen, settle_after=not chunked
                )
            if seen():
                break
            if ctx.overshoots(s):  # a recovery demonstration: on to the limit, then back
                limit = embodiment.TORSO_YAW_RANGE[int(views[s][0] > 0)]
                yield from move_head_torso_to(ctx, limit, views[s][1], CAMERA_SEARCH, stop_when=seen)
                if seen():
                    break
            if chunked:
                yield from ctx.await_decision()
            else:
                yield from hold(ctx, 2)  # let the view settle before declaring the sector empty
            ctx.explored.add(s)
            if seen():
                break
        else:
            raise ExpertError(f"{ctx.objects[i]} not found in any search sector")
    it.stage = STAGE_ANCHOR
    it.info_complete = True
    if center:
        yield from look_at(ctx, ctx.memory[i])


def sweep_all(ctx: ExpertContext, targets: list[int]) -> Actions:
    """Visit every sector (nearest first) so all of ``targets`` that exist get observed."""
    it = ctx.intent
    it.stage, it.info_complete = STAGE_SEARCH, False
    it.search_targets = it.search_targets | set(targets)
    lower = [s for s, (_, pitch) in enumerate(ctx.views) if pitch == SEARCH_PITCH]
    upper = [s for s in range(len(ctx.views)) if s not in lower]
    # Each row of sectors: to its nearer end first, then across to the other end.
    for row in (lower, upper) if upper else (lower,):
        centre = next(s for s in row if ctx.views[s][0] == 0.0)
        ends = sorted([s for s in row if s != centre], key=lambda s: abs(ctx.views[s][0] - ctx.yaw))
        at_centre = ctx.yaw == 0.0 and (row is lower or ctx.pitch == ctx.views[centre][1])
        for s in ends if at_centre else [*ends, centre]:
            yield from move_head_torso_to(ctx, *ctx.views[s], CAMERA_SEARCH)
            yield from hold(ctx, 3)
            ctx.explored.add(s)
        ctx.explored.add(centre)
    it.info_complete = True
