"""Idioms the task experts share, built from the primitives: find an object and face it with the
arm that will act, press an object at its press point, and finish (retreat and hold)."""

from __future__ import annotations

from collections.abc import Generator

import numpy as np

from . import primitives
from .context import ExpertContext


def find_and_face(
    ctx: ExpertContext, i: int, side: str | None = None, then=None
) -> Generator[np.ndarray, None, str]:
    """Search for object ``i`` (from memory or by sector sweep), choose the arm (``side``, or the one
    on the object's half of the fan; with a known destination ``then``, the half of the midpoint)
    and turn the torso so the object sits in front of it. Returns the arm: ``side = yield from ...``."""
    yield from primitives.search(ctx, i, center=False)
    side = side or primitives.arm_for(ctx.memory[i], then)
    yield from primitives.face_for_arm(ctx, ctx.memory[i], side)
    return side


def nearest_known(ctx: ExpertContext, candidates: list[int]) -> int:
    """The candidate the expert has seen that is nearest the current heading (else the first):
    where to go next without a detour."""
    known = [i for i in candidates if i in ctx.memory]
    if not known:
        return candidates[0]
    heading = np.pi / 2 + ctx.yaw
    return min(known, key=lambda i: abs(np.arctan2(ctx.memory[i][1], ctx.memory[i][0]) - heading))


def press_point(ctx: ExpertContext, i: int) -> np.ndarray:
    """World position of object ``i``'s registered press point (``functional.press``, in the frame
    of the moving part it is on when it has one: a rocker, a stapler arm)."""
    press = ctx.obj(i).functional.press
    if press.body is not None:
        body = ctx.sim.data.body(press.body)
        pos, rot = body.xpos.copy(), body.xmat.reshape(3, 3).copy()
    else:
        pos, rot = ctx.pose(i)
    return pos + rot @ np.asarray(press.point)


def press_object(ctx: ExpertContext, side: str, i: int, depth: float):
    """Closed fingertips pressed ``depth`` m into object ``i``'s press point, then lifted off."""
    yield from primitives.press(ctx, side, press_point(ctx, i), depth=depth, targets={i})


def finish(ctx: ExpertContext, side: str, hold: int = 3):
    """Return the arm home with the gripper open, then hold still."""
    yield from primitives.retreat(ctx, side)
    yield from primitives.hold(ctx, hold)
