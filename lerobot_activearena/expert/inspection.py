"""Interactive inspection (IA tasks): pick an object up so that the wrist can later turn it, turn
its hidden information face (a back patch, a date label) to the head camera, and turn it back.

    turn = yield from pick_for_inspection(ctx, i)
    yield from show_hidden_face(ctx, turn, i)   # returns once the camera sees the face
    ... read the information (the task knows what it is) ...
    yield from restore_pose(ctx, turn, i)
"""

from __future__ import annotations

import math
from collections.abc import Generator
from dataclasses import dataclass

import numpy as np

from ..annotations.schema import CAMERA_INSPECT, STAGE_ANCHOR, STAGE_SEARCH
from ..sim import embodiment
from ..sim.head_camera import hidden_face_visible
from ..sim.workspace import TABLE_TOP
from . import arm_paths, motion, routines, skills, view_moves
from .context import ExpertContext, ExpertError
from .ik import grasp_rotation, rot_z

LIFT = 0.16  # m: clear of the table and of neighbours while turning
INSPECT_R = (0.34, 0.42)  # m: radii from which an object can be lifted this high and turned by either arm
FACE_WAIT = 6  # frames to wait for the face to come into view


# Farther out (and higher), the head camera sees a vertical face less obliquely: candidate
# (forward m, height m) spots in front of the arm's shoulder for information that must be read in
# detail (a printed date); the most frontal one where the wrist can make the whole turn is used.
SHOW_SPOTS = ((0.4, 1.05), (0.42, 1.0), (0.55, 0.95), (0.5, 0.95), (0.5, 0.9), (0.45, 0.95))


@dataclass
class Turn:
    """How a picked object gets shown: the arm, where it is turned and by how much (rad), and the
    arm's joints before the turn (``q_before``, set while showing; the way back)."""

    side: str
    point: np.ndarray
    angle: float
    q_before: np.ndarray | None = None


def inspect_points(
    ctx: ExpertContext, side: str, hang: float = 0.0, fine_print: bool = False
) -> list[np.ndarray]:
    """Where to turn the object, in order of preference: in front of the arm's shoulder, below the
    head (the wrist can turn there and the camera sees it), after the ``SHOW_SPOTS`` with
    ``fine_print``. Raised for objects hanging far below the TCP (``hang``): 8 cm table clearance."""
    lateral = -0.19 if side == "left" else 0.19
    c, s = math.cos(ctx.yaw), math.sin(ctx.yaw)
    spots = [*(SHOW_SPOTS if fine_print else ()), (0.38, 0.87)]
    return [
        np.array([c * lateral - s * f, s * lateral + c * f, max(z, TABLE_TOP + hang + 0.08)])
        for f, z in spots
    ]


def turn_angles(ctx: ExpertContext, i: int, point) -> list[float]:
    """Turns (rad, about the vertical) that would show object ``i``'s face to the head camera from
    ``point``, best first: exactly facing it (either way round), then 25 / 50 deg off (oblique)."""
    _, body_rot = ctx.pose(i)
    normal = body_rot @ np.asarray(ctx.obj(i).functional.info_face.normal)
    cam = ctx.sim.data.cam_xpos[ctx.sim.model.camera(embodiment.HEAD_CAMERA).id]
    want = math.atan2(cam[1] - point[1], cam[0] - point[0]) - math.atan2(normal[1], normal[0])
    base = math.remainder(want, 2 * math.pi)
    other = base - math.copysign(2 * math.pi, base)
    return [
        a + off
        for off in (0.0, 0.45, -0.45, 0.9, -0.9)
        for a in (base, other)
        if abs(a + off) <= 1.2 * math.pi
    ]


def _grasp_for_turn(
    ctx: ExpertContext, side: str, i: int, points, lift: float
) -> tuple[np.ndarray, float, np.ndarray]:
    """Finger-closing axis (+/- the object's y: the face on its +x stays uncovered), turn angle and
    inspection point: the first whose carry and whole turn IK can follow (the angles of
    ``turn_angles`` in order of obliqueness, then the points in order)."""
    _, body_rot = ctx.pose(i)
    grasp = skills.grasp_point(ctx, i)
    path = [grasp + [0, 0, 0.12], grasp, grasp + [0, 0, lift]]
    # Exactly facing the camera from any point beats an oblique view from a preferred one.
    ranked = sorted(
        ((k // 2, n, p, a) for n, p in enumerate(points) for k, a in enumerate(turn_angles(ctx, i, p))),
        key=lambda c: c[:2],
    )
    for _, _, point, angle, sign in ((*c, g) for c in ranked for g in (1.0, -1.0)):
        rot = grasp_rotation([0, 0, -1], sign * body_rot[:, 1])
        try:
            q = motion.arm_of(ctx.action, side)
            for pos in path:
                q = arm_paths.solve_ik(ctx, side, q, pos, rot)
            # The carry to the inspection point and the turn, as carry_and_turn will follow them.
            top = path[-1]
            for frac in np.linspace(0.0, 1.0, 13)[1:]:
                q = arm_paths.solve_ik(
                    ctx,
                    side,
                    q,
                    top + frac * (point - top),
                    rot_z(frac * angle) @ rot,
                    max_step=arm_paths.MAX_PATH_STEP,
                )
            return sign * body_rot[:, 1], angle, point
        except ExpertError:
            continue
    raise ExpertError(f"the {side} wrist cannot turn {ctx.objects[i]} to show its hidden face")


def pick_for_inspection(
    ctx: ExpertContext, i: int, lift: float = LIFT, fine_print: bool = False
) -> Generator[np.ndarray, None, Turn]:
    """Find object ``i``, face it and pick it with a grasp the wrist can turn: ``turn = yield from ...``.
    ``fine_print``: the face must be read in detail; turn it where the camera sees it most frontally."""
    side = yield from routines.find_and_face(ctx, i)
    points = inspect_points(ctx, side, float(skills.grasp_point(ctx, i)[2]) - ctx.bottom_z(i), fine_print)
    closing, angle, point = _grasp_for_turn(ctx, side, i, points, lift)
    yield from skills.pick(ctx, side, i, closing=closing, lift=lift, flip_ok=False)
    return Turn(side, point, angle)


def show_hidden_face(ctx: ExpertContext, turn: Turn, i: int):
    """Carry object ``i`` to the inspection point, turn it and look at it until the head camera
    sees its information face (the information-revealing action); raises if it never does."""
    it = ctx.intent
    it.stage, it.info_complete, it.focus = STAGE_SEARCH, False, i
    turn.q_before = motion.arm_of(ctx.action, turn.side).copy()
    yield from skills.carry_and_turn(ctx, turn.side, turn.point, turn.angle)
    it.stage = STAGE_ANCHOR
    yaw, pitch = ctx.gaze.aim(ctx.center(i), ctx.yaw, ctx.pitch, fix_yaw=True)
    yield from view_moves.move_head_torso_to(ctx, yaw, pitch, CAMERA_INSPECT)
    info = ctx.obj(i)
    for _ in range(FACE_WAIT):
        if hidden_face_visible(ctx.sim.model, ctx.sim.data, info):
            break
        yield from motion.hold(ctx, 1)
    else:
        raise ExpertError(f"the hidden face of {ctx.objects[i]} never came into view")
    it.info_complete = True
    # The view that revealed it, for the sidecar (record_reading adds what was read and decided).
    ctx.notes.setdefault("inspections", []).append(
        {
            "object": ctx.objects[i],
            "frame": ctx.frame,
            "torso_yaw": round(ctx.yaw, 4),
            "head_pitch": round(ctx.pitch, 4),
        }
    )
    yield from motion.hold(ctx, 3)


def record_reading(ctx: ExpertContext, i: int, reading, decision: str) -> None:
    """Link the last inspection of object ``i`` to what was read off it and the decision it supports."""
    for entry in reversed(ctx.notes.get("inspections", [])):
        if entry["object"] == ctx.objects[i]:
            entry.update(reading=reading, decision=decision)
            return
    raise ExpertError(f"{ctx.objects[i]} was read without being inspected")


def restore_pose(ctx: ExpertContext, turn: Turn, i: int):
    """Turn the carried object back to its picked orientation (placement-ready): the arm returns
    to its joints before the turn."""
    skills.start_action(ctx, {i})
    ctx.intent.carried = {i}
    yield from arm_paths.move_arm_joint(ctx, turn.side, turn.q_before, max_vel=1.5)
