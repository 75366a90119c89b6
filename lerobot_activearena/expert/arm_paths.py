"""Arm paths of the expert: IK with fallbacks, joint-space moves (the paper's move_joint), straight
TCP lines (IK every step), the gripper and grasp orientations. Generators of 18-D actions that move arms only.
"""

from __future__ import annotations

import math

import numpy as np

from ..annotations.schema import (
    CAMERA_HOLD,
)
from ..sim import embodiment
from .context import ExpertContext, ExpertError
from .ik import IKError, grasp_rotation, interpolate_pose, rot_z
from .motion import CONTROL_DT, Actions, arm_of, gripper_index, interpolate_joints, with_arm

MAX_PATH_STEP = 0.5  # rad: a joint may move this much between two waypoints of a continuous path


def solve_ik(ctx: ExpertContext, side: str, q_seed, pos, rot, max_step: float | None = None) -> np.ndarray:
    """IK from ``q_seed``; on failure, once more from the home configuration with more iterations
    (along a continuous path, ``max_step``, only if that lands on the seed's branch: a jump to
    another branch would whip the arm and what it holds)."""
    try:
        return ctx.ik.solve(side, q_seed, ctx.yaw, pos, rot)
    except IKError:
        pass
    try:
        q = ctx.ik.solve(side, embodiment.HOME_ARM[side], ctx.yaw, pos, rot, max_iters=800)
        if max_step is None or np.abs(q - np.asarray(q_seed)).max() <= max_step:
            return q
    except IKError:
        pass
    try:  # near-converged (a few mm) is fine along a path; endpoints are re-checked by physics
        return ctx.ik.solve(side, q_seed, ctx.yaw, pos, rot, max_iters=400, pos_tol=8e-3, rot_tol=5e-2)
    except IKError as exc:
        raise ExpertError(str(exc)) from exc


def tcp_pose(ctx: ExpertContext, side: str) -> tuple[np.ndarray, np.ndarray]:
    return ctx.ik.tcp_pose(side, arm_of(ctx.action, side), ctx.yaw)


def move_arm_joint(
    ctx: ExpertContext, side: str, q_goal, gripper: float | None = None, max_vel: float = 1.0
) -> Actions:
    """The paper's move_joint: linear joint path at <= max_vel rad/s with a smooth time scaling."""
    ctx.require_idle(side)
    ctx.intent.camera_mode = CAMERA_HOLD
    q0 = arm_of(ctx.action, side)
    for q in interpolate_joints(q0, np.asarray(q_goal, float), max_vel=max_vel):
        ctx.action = with_arm(ctx.action, side, q, gripper)
        yield ctx.emit()


def arm_goto(
    ctx: ExpertContext, side: str, pos, rot, gripper: float | None = None, max_vel: float = 1.5
) -> Actions:
    q_goal = solve_ik(ctx, side, arm_of(ctx.action, side), pos, rot)
    yield from move_arm_joint(ctx, side, q_goal, gripper, max_vel)


def line_path(
    ctx: ExpertContext,
    side: str,
    pos,
    rot,
    speed: float = 0.15,
    turn_speed: float | None = None,
    yaw_turn: float | None = None,
) -> list[np.ndarray]:
    """The arm's joint waypoints of a straight TCP segment with a smooth (cosine) speed profile peaking
    at ``speed`` m/s (and, with ``turn_speed``, the wrist's turn peaking at that many rad/s: a carried
    object does not swing); ``yaw_turn``: the wrist turns by this angle (rad, either way, any size)
    about the vertical instead of the short way to ``rot``. Raises ExpertError where IK loses the path."""
    q = arm_of(ctx.action, side)
    p0, rot0 = tcp_pose(ctx, side)
    dist = float(np.linalg.norm(np.asarray(pos) - p0))
    n = max(3, int(math.ceil(dist * math.pi / 2 / (speed * CONTROL_DT))))
    if turn_speed is not None:
        angle = math.acos(np.clip((np.trace(rot0.T @ np.asarray(rot)) - 1.0) / 2.0, -1.0, 1.0))
        angle = angle if yaw_turn is None else abs(yaw_turn)
        n = max(n, int(math.ceil(angle * math.pi / 2 / (turn_speed * CONTROL_DT))))
    path = []
    for k in range(1, n + 1):
        s = 0.5 - 0.5 * math.cos(math.pi * k / n)
        pk, rot_k = interpolate_pose(p0, rot0, pos, rot, s)
        if yaw_turn is not None:
            rot_k = rot if k == n else rot_z(s * yaw_turn) @ rot0
        q = solve_ik(ctx, side, q, pk, rot_k, max_step=MAX_PATH_STEP)
        path.append(q)
    return path


def follow(ctx: ExpertContext, side: str, path, gripper: float | None = None) -> Actions:
    ctx.require_idle(side)
    ctx.intent.camera_mode = CAMERA_HOLD
    for q in path:
        ctx.action = with_arm(ctx.action, side, q, gripper)
        yield ctx.emit()


def arm_line(
    ctx: ExpertContext,
    side: str,
    pos,
    rot,
    gripper: float | None = None,
    speed: float = 0.15,
) -> Actions:
    """Straight TCP segment (``line_path``)."""
    yield from follow(ctx, side, line_path(ctx, side, pos, rot, speed), gripper)


def set_gripper(ctx: ExpertContext, side: str, value: float, steps: int) -> Actions:
    ctx.require_idle(side)
    g = gripper_index(side)
    v0 = ctx.action[g]
    for k in range(1, steps + 1):
        ctx.action[g] = v0 + (value - v0) * min(1.0, k / max(1, steps // 2))
        yield ctx.emit()


def top_down_rotation(ctx: ExpertContext, side: str, closing, *positions) -> np.ndarray:
    """Gripper pointing down with fingers closing along +/-``closing``: the sign nearest the current
    wrist with which IK reaches every one of ``positions``."""
    _, rot_now = tcp_pose(ctx, side)
    c = np.array([closing[0], closing[1], 0.0])
    c /= np.linalg.norm(c)
    cands = sorted(
        [grasp_rotation([0, 0, -1], c), grasp_rotation([0, 0, -1], -c)],
        key=lambda r: -np.trace(rot_now.T @ r),
    )
    for rot in cands:
        try:
            for pos in positions:
                solve_ik(ctx, side, arm_of(ctx.action, side), pos, rot)
            return rot
        except ExpertError:
            continue
    raise ExpertError(f"{side} arm cannot reach top-down poses at {np.round(positions, 3).tolist()}")


def radial_tangent(point) -> np.ndarray:
    """Horizontal direction perpendicular to the robot-to-point ray (fingers close sideways)."""
    radial = np.array([point[0], point[1], 0.0]) / np.linalg.norm(point[:2])
    return np.array([-radial[1], radial[0], 0.0])


def box_closing_axis(ctx: ExpertContext, i: int, prefer_y: bool = False) -> np.ndarray:
    """Finger-closing axis for a box-like object: the asset's ``functional.grasp_axis`` where it
    declares one, else the body axis nearest the tangential direction (or its body y axis with
    ``prefer_y``, which keeps the +x face free)."""
    p, rot = ctx.pose(i)
    declared = ctx.obj(i).functional.grasp_axis
    if declared is not None:
        return rot @ np.asarray(declared, float)
    if prefer_y:
        return rot[:, 1]
    radial = np.array([p[0], p[1], 0.0]) / np.linalg.norm(p[:2])
    tangential = np.array([-radial[1], radial[0], 0.0])
    return max((rot[:, 0], rot[:, 1]), key=lambda ax: abs(ax @ tangential))
