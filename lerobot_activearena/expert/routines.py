"""Idioms the task experts share, built from the primitives: find an object and face it with the
arm that will act, press an object at its press point, pick an object and set it down on a
destination or a spot, and finish (retreat and hold)."""

from __future__ import annotations

import math
from collections.abc import Generator

import numpy as np

from ..sim.workspace import TABLE_TOP
from . import arm_paths, motion, skills, view_moves
from .context import ExpertContext


def find_and_face(
    ctx: ExpertContext, i: int, side: str | None = None, then=None
) -> Generator[np.ndarray, None, str]:
    """Search for object ``i`` (from memory or by sector sweep), choose the arm (``side``, or the one
    on the object's half of the fan; with a known destination ``then``, the half of the midpoint)
    and turn the torso so the object sits in front of it. Returns the arm: ``side = yield from ...``."""
    yield from view_moves.search(ctx, i, center=False)
    side = side or skills.arm_for(ctx.memory[i], then)
    yield from view_moves.face_for_arm(ctx, ctx.memory[i], side)
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
    yield from skills.press(ctx, side, press_point(ctx, i), depth=depth, targets={i})


def finish(ctx: ExpertContext, side: str, hold: int = 3):
    """Return the arm home with the gripper open, then hold still."""
    yield from skills.retreat(ctx, side)
    yield from motion.hold(ctx, hold)


GRASP_ACROSS = ("box", "radial")


def surface_z(ctx: ExpertContext, dest: int) -> float:
    """Height an object is set down at on ``dest``: a container's inner floor, else the top of its
    box (a pad's, mat's, plate's or stand's top is the top of its box)."""
    box = ctx.obj(dest).functional.container
    if box is not None:
        p, _ = ctx.pose(dest)
        return float(p[2] + box.floor)
    return ctx.top_z(dest)


def pick_and_place(
    ctx: ExpertContext,
    obj: int,
    dest: int | None = None,
    spot=None,
    subtasks: tuple[int, int] = (1, 2),
    side: str | None = None,
    grasp_across: str = "box",
    lift: float = 0.12,
    approach: float = 0.12,
    hover: float = 0.10,
    above: float = 0.002,
    finish_after: bool = True,
    face_robot: bool = False,
    carry_in: float | None = None,
    straight_approach: bool = False,
    set_down=None,
) -> Generator[np.ndarray, None, str]:
    """Find object ``obj`` and pick it up (subtask ``subtasks[0]``; the arm on its half of the fan
    unless ``side``), then find the destination object ``dest`` and set ``obj`` down on its centre
    (or carry it to ``spot``: a table point (x, y), or (x, y, surface z)), release it and, with
    ``finish_after``, retreat (subtask ``subtasks[1]``). ``grasp_across``: 'box' (fingers across
    the object's box) or 'radial' (across the line from the robot's base: round objects). Keeps the
    intent up to date (what is carried, the action's targets).
    ``lift`` / ``approach`` / ``hover``: how high the object is lifted, how high above the grasp
    point the gripper comes in, how high above the set-down pose it carries the object in.
    ``face_robot``: set ``obj`` down with its ``functional.front`` towards the robot's base.
    ``carry_in``: pull the held object in to this distance from the robot's base before the torso
    turns (a long object swings wide). ``straight_approach``: see ``skills.pick``. ``set_down``: a
    function of the destination's centre giving the table point (x, y) to set ``obj`` down at instead
    of the destination's top (placing beside it). Returns the arm."""
    if (dest is None) == (spot is None):
        raise ValueError("pick_and_place needs exactly one of a destination object (dest) or a spot")
    if grasp_across not in GRASP_ACROSS:
        raise ValueError(f"grasp_across must be one of {GRASP_ACROSS}, got {grasp_across!r}")
    with ctx.subtask(subtasks[0]):
        side = yield from find_and_face(ctx, obj, side)
        closing = arm_paths.radial_tangent(ctx.center(obj)) if grasp_across == "radial" else None
        yield from skills.pick(
            ctx, side, obj, closing=closing, lift=lift, approach=approach, straight_approach=straight_approach
        )
    with ctx.subtask(subtasks[1]):
        if carry_in is not None:
            yield from skills.pull_in(ctx, side, carry_in)
        if dest is not None:
            yield from find_and_face(ctx, dest, side)
            skills.start_action(ctx, {obj, dest})
            if set_down is None:
                target, z = ctx.center(dest)[:2], surface_z(ctx, dest)
            else:  # beside the destination: turn to the spot
                target, z = np.asarray(set_down(ctx.center(dest)), float)[:2], TABLE_TOP
                yield from view_moves.face_for_arm(ctx, np.array([*target, z]), side)
        else:
            target, z = np.asarray(spot, float)[:2], float(spot[2]) if len(spot) > 2 else TABLE_TOP
            yield from view_moves.face_for_arm(ctx, np.array([*target, z]), side)
            skills.start_action(ctx, {obj})
        yaw = facing_robot_yaw(ctx.obj(obj), target) if face_robot else None
        yield from skills.place(ctx, side, obj, target, z + above, obj_yaw=yaw, hover=hover)
        if finish_after:
            yield from finish(ctx, side)
    return side


def facing_robot_yaw(obj, target_xy) -> float:
    """The body yaw that turns ``obj``'s ``functional.front`` towards the robot's base from ``target_xy``."""
    front = obj.functional.front
    if front is None:
        raise ValueError(f"{obj.name} ({obj.category}) declares no front to turn towards the robot")
    to_robot = math.atan2(-target_xy[1], -target_xy[0])
    return to_robot - math.atan2(front[1], front[0])
