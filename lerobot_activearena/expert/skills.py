"""Skills of the expert, built from arm paths: ``pick``, ``place`` (and ``place_on_upper``), ``press``,
``strike``, ``pull_in``, ``hold_aside``, ``carry_and_turn``, ``retreat``, and the choice of arm
(``arm_for``).
"""

from __future__ import annotations

import math

import numpy as np

from ..annotations.schema import (
    CAMERA_HOLD,
    STAGE_ACTION,
)
from ..sim import embodiment
from .arm_paths import (
    MAX_PATH_STEP,
    arm_goto,
    arm_line,
    box_closing_axis,
    follow,
    line_path,
    move_arm_joint,
    set_gripper,
    solve_ik,
    tcp_pose,
    top_down_rotation,
)
from .context import ExpertContext, ExpertError
from .gaze import heading_deg
from .ik import grasp_rotation, rot_z
from .motion import CONTROL_DT, Actions, arm_of, hold, interpolate_joints, with_arm

FINGERTIP_CLOSED = 0.047  # closed fingertips reach this far past the TCP along the approach axis


PLACE_TURN_SPEED = 2.5  # rad/s: peak wrist turn when an object is turned to a set yaw while carried


GRASP_Z_MIN_ABOVE_BOTTOM = 0.033  # open pads reach 0.028 m past the TCP: keep them off the table


def start_action(ctx: ExpertContext, targets: set[int]) -> None:
    ctx.intent.stage = STAGE_ACTION
    ctx.intent.action_targets = set(targets)
    ctx.intent.camera_mode = CAMERA_HOLD


def grasp_point(ctx: ExpertContext, i: int) -> np.ndarray:
    """Where the TCP closes on object ``i``: its first registered grasp point (``functional.grasp``, body frame; tall
    objects are held high so the palm clears their top), else its centre kept high enough that the
    open pads stay off the table."""
    grasp = ctx.obj(i).functional.grasp
    if grasp:
        local = grasp[0]
        p, rot = ctx.pose(i)
        return p + rot @ np.asarray(local, float)
    c = ctx.center(i)
    return np.array([c[0], c[1], max(c[2], ctx.bottom_z(i) + GRASP_Z_MIN_ABOVE_BOTTOM)])


def pick(
    ctx: ExpertContext,
    side: str,
    i: int,
    closing=None,
    lift: float = 0.15,
    flip_ok: bool = True,
    approach: float = 0.12,
    straight_approach: bool = False,
    max_vel: float = 1.5,
) -> Actions:
    """Top-down grasp of object ``i`` from ``approach`` m above the grasp point, and lift. A grasp
    that did not bring the object up is let go and tried once more from above (after a second miss:
    ExpertError). ``flip_ok=False`` keeps the finger order given by ``closing`` (no 180 deg wrist
    flip). ``straight_approach``: the gripper rises to the approach height and comes in along straight
    lines (a tall object: the approach's joint path dips and sweeps over it). ``max_vel``: the joints'
    peak speed (rad/s) on the way to the approach pose. With ``ctx.grasp_miss`` the first try runs
    with the arm off its command (``_miss_first_grasp``)."""
    start_action(ctx, {i})
    closing = box_closing_axis(ctx, i) if closing is None else closing
    for attempt in range(GRASP_TRIES):
        grasp = grasp_point(ctx, i)
        if flip_ok:
            rot = top_down_rotation(ctx, side, closing, grasp + [0, 0, approach], grasp, grasp + [0, 0, lift])
        else:
            rot = grasp_rotation([0, 0, -1], [closing[0], closing[1], 0.0])
        z0 = ctx.bottom_z(i)
        missing = attempt == 0 and ctx.grasp_miss > 0.0 and _miss_first_grasp(ctx, side, grasp, rot, closing)
        start = ctx.frame
        if straight_approach:
            p, rot_now = tcp_pose(ctx, side)
            if p[2] < grasp[2] + approach:
                yield from arm_line(ctx, side, [p[0], p[1], grasp[2] + approach], rot_now, 1.0, speed=0.25)
            yield from arm_line(ctx, side, grasp + [0, 0, approach], rot, 1.0, speed=0.25)
        else:
            yield from arm_goto(ctx, side, grasp + [0, 0, approach], rot, gripper=1.0, max_vel=max_vel)
        yield from arm_line(ctx, side, grasp, rot, 1.0, speed=0.18)
        yield from set_gripper(ctx, side, 0.0, 10)
        ctx.intent.carried = {i}
        yield from arm_line(ctx, side, grasp + [0, 0, lift], rot, 0.0, speed=0.2)
        ctx.executed_offset = None
        rose = ctx.bottom_z(i) - z0
        if rose >= 0.5 * lift:
            if missing:
                raise ExpertError(f"the missed grasp demonstrated on {ctx.objects[i]} caught it")
            return
        ctx.intent.carried = set()
        if missing:  # the frames whose arm ran off its command, and the hold while it comes back
            ctx.notes.setdefault("grasp_misses", []).append([start, ctx.frame + GRASP_SETTLE])
        if attempt + 1 < GRASP_TRIES:  # let go; the next try comes in from above the object again
            yield from hold(ctx, GRASP_SETTLE)
            yield from set_gripper(ctx, side, 1.0, 6)
    raise ExpertError(f"grasp of {ctx.objects[i]} failed: it rose {100 * rose:.1f} cm")


GRASP_TRIES = 2  # a missed grasp is tried once more
GRASP_SETTLE = 4  # frames the arm holds after a miss before it lets go (an offset arm comes back)


def _miss_first_grasp(ctx: ExpertContext, side: str, grasp: np.ndarray, rot: np.ndarray, closing) -> bool:
    """Grasp-retry demonstrations: set ``ctx.executed_offset`` so that the arm the simulator moves
    closes 0.5-1 x ``ctx.grasp_miss`` m above the grasp point and as far beside it, across the
    fingers' closing axis (the fingers pass beside the object), on nothing: the joints' difference
    between the two IK solutions. The draws come from the episode's own stream, so the scene is
    untouched; False where IK cannot reach the offset pose."""
    up, across, sign = ctx.miss_rng.uniform([GRASP_MISS_MIN, GRASP_MISS_MIN, -1.0], [1.0, 1.0, 1.0])
    c = np.asarray(closing, float)[:2]
    perpendicular = np.array([-c[1], c[0]]) / np.linalg.norm(c)
    offset = ctx.grasp_miss * np.array([*(math.copysign(across, sign) * perpendicular), up])
    try:
        q_grasp = solve_ik(ctx, side, arm_of(ctx.action, side), grasp, rot)
        q_off = solve_ik(ctx, side, q_grasp, grasp + offset, rot)
    except ExpertError:
        return False
    ctx.executed_offset = with_arm(np.zeros_like(ctx.action), side, q_off - q_grasp)
    return True


GRASP_MISS_MIN = 0.5  # the missed grasp's least height above and distance beside, as a part of grasp_miss


def _feasible_rotation(
    ctx: ExpertContext, side: str, rot: np.ndarray, positions, yaw_free: bool
) -> np.ndarray:
    """``rot``, or (when the carried object is symmetric enough, ``yaw_free``) rot turned about the
    vertical by 90/-90/180 deg: the first with which IK reaches all ``positions``."""
    turns = (0.0, math.pi / 2, -math.pi / 2, math.pi) if yaw_free else (0.0,)
    for th in turns:
        turn_rot = rot_z(th)
        try:
            for pos in positions:
                solve_ik(ctx, side, arm_of(ctx.action, side), pos, turn_rot @ rot)
            return turn_rot @ rot
        except ExpertError:
            continue
    raise ExpertError(f"{side} arm cannot reach the placement poses {np.round(positions, 3).tolist()}")


def place(
    ctx: ExpertContext,
    side: str,
    i: int,
    target_xy,
    surface_z: float,
    clearance: float = 0.006,
    yaw_free: bool = True,
    obj_yaw: float | None = None,
    hover: float = 0.10,
    slow_last: float | None = None,
) -> Actions:
    """Carry object ``i`` over ``target_xy``, lower its bottom to ``surface_z + clearance``, release, rise.
    ``obj_yaw``: the world yaw (rad) the object's body x axis must end at (the wrist turns the object
    there); None: any yaw (with ``yaw_free`` the wrist may turn it by quarter turns to reach).
    ``hover``: how high above the set-down pose it comes in and the gripper rises after.
    ``slow_last``: lower at carrying speed down to this many m above the set-down pose, then slowly
    (None: slowly all the way)."""
    p, rot = tcp_pose(ctx, side)
    if obj_yaw is not None:
        _, obj_rot = ctx.pose(i)
        turn = obj_yaw - math.atan2(obj_rot[1, 0], obj_rot[0, 0])
        rot = rot_z(math.atan2(math.sin(turn), math.cos(turn))) @ rot
        yaw_free = False
    c = ctx.center(i)
    offset = rot.T @ np.array([*(p[:2] - c[:2]), 0.0])  # TCP offset from the object centre, gripper frame
    tcp_above_bottom = p[2] - ctx.bottom_z(i)

    def tcp_for(grip_rot, z):
        off = grip_rot @ offset
        return np.array([target_xy[0] + off[0], target_xy[1] + off[1], z])

    z_down = surface_z + clearance + tcp_above_bottom
    z_above = max(z_down + hover, p[2])
    grip_rot = _feasible_rotation(ctx, side, rot, [tcp_for(rot, z_above), tcp_for(rot, z_down)], yaw_free)
    if obj_yaw is None:
        yield from arm_line(ctx, side, tcp_for(grip_rot, z_above), grip_rot, 0.0, speed=0.25)
    else:
        yield from follow(ctx, side, _turning_carry(ctx, side, tcp_for(grip_rot, z_above), grip_rot), 0.0)
    if slow_last is not None and z_above - z_down > slow_last:
        yield from arm_line(ctx, side, tcp_for(grip_rot, z_down + slow_last), grip_rot, 0.0, speed=0.25)
    yield from arm_line(ctx, side, tcp_for(grip_rot, z_down), grip_rot, 0.0, speed=0.12)
    yield from set_gripper(ctx, side, 1.0, 6)
    ctx.intent.carried = set()
    yield from arm_line(ctx, side, tcp_for(grip_rot, z_down + hover), grip_rot, 1.0, speed=0.2)


def place_on_upper(
    ctx: ExpertContext,
    side: str,
    i: int,
    target_xy,
    surface_z: float,
    clearance: float = 0.006,
    entry_r: float = 0.50,
    over: float = 0.03,
    drop: bool = False,
    from_shoulder: bool = False,
) -> Actions:
    """Set held object ``i`` down on the upper band, where no top-down pose reaches: the wrist turns
    horizontal (approach along the line from the robot's base, fingers closing across it), the
    object comes in at ``entry_r`` m from the base, ``over`` m above its set-down height (below the
    gripper nothing but the slab's edge), slides out over ``target_xy``, is lowered to
    ``surface_z + clearance`` and released; the gripper backs out the way it came. ``drop``: release
    it at the height it came in (into a container, whose walls keep the gripper out).
    ``from_shoulder``: approach along the line from the arm's shoulder instead (the wrist stays
    clear of its limits where the arm reaches high across the torso's heading)."""
    p, rot = tcp_pose(ctx, side)
    _, obj_rot = ctx.pose(i)
    centre = ctx.center(i)
    origin = ctx.ik.shoulder(side, ctx.yaw)[:2] if from_shoulder else np.zeros(2)
    u = np.array([*(np.asarray(target_xy[:2]) - origin), 0.0])
    u /= np.linalg.norm(u)
    tangent = np.array([-u[1], u[0], 0.0])
    # the fingers keep closing along (+/-) the tangent: the sign nearest the current closing axis
    grip = grasp_rotation(u, tangent if rot[:, 0] @ tangent >= 0 else -tangent)
    turn = grip @ rot.T  # the held object turns rigidly with the wrist
    off = rot.T @ (centre - p)  # object centre in the gripper frame
    half = np.asarray(ctx.obj(i).half_extents, float)
    half_h = float(np.abs((turn @ obj_rot)[2]) @ half)  # its vertical half-extent once turned

    def tcp_at(xy, z_bottom):
        c = np.array([xy[0], xy[1], z_bottom + half_h])
        return c - grip @ off

    z_down = surface_z + clearance
    entry = tcp_at(target_xy[:2] - (np.linalg.norm(target_xy[:2]) - entry_r) * u[:2], z_down + over)
    above = tcp_at(target_xy, z_down + over)
    down = tcp_at(target_xy, z_down)
    for pose in (entry, above, down):
        solve_ik(ctx, side, arm_of(ctx.action, side), pose, grip)
    yield from arm_goto(ctx, side, entry, grip, gripper=0.0, max_vel=1.6)
    yield from arm_line(ctx, side, above, grip, 0.0, speed=0.45)
    if drop:
        down = above
    else:
        yield from arm_line(ctx, side, down, grip, 0.0, speed=0.12)
    yield from set_gripper(ctx, side, 1.0, 4)
    ctx.intent.carried = set()
    # back out level, the open fingers either side of the object, to inside the band's inner edge,
    # then drop below the slab: the joint path home must not sweep the fingers through its edge
    back = entry if drop else entry + [0, 0, down[2] + 0.01 - entry[2]] - 0.05 * u
    yield from arm_line(ctx, side, back, grip, 1.0, speed=0.5)
    upper = ctx.sim.info.workspace.level(1)
    below = back - (0.08 if drop else 0.0) * u  # from high up the wrist reaches down only inwards
    yield from arm_line(
        ctx, side, [below[0], below[1], upper.top_z - upper.thickness - 0.08], grip, 1.0, speed=0.6
    )


def _turning_carry(ctx: ExpertContext, side: str, pos, rot) -> list[np.ndarray]:
    """Joint path that carries the held object to ``pos`` while the wrist turns it about the vertical
    to ``rot``: along a straight line turning the short way, else the long way (where the short way
    runs the wrist into a joint limit)."""
    _, rot0 = tcp_pose(ctx, side)
    rel = np.asarray(rot) @ rot0.T  # a turn about the world vertical
    short = math.atan2(rel[1, 0], rel[0, 0])
    for turn in (short, short - math.copysign(2 * math.pi, short)):
        try:
            return line_path(ctx, side, pos, rot, 0.25, PLACE_TURN_SPEED, yaw_turn=turn)
        except ExpertError:
            continue
    raise ExpertError(f"{side} arm cannot turn the held object to its set-down yaw on the way to {pos}")


def press(
    ctx: ExpertContext, side: str, point, depth: float, targets: set[int], approach: float = 0.07
) -> Actions:
    """Closed fingertips pressed ``depth`` m into ``point`` from above, then released. The wrist's
    rotation about the vertical is free: the first one IK reaches along the whole stroke is used."""
    start_action(ctx, targets)
    radial = np.array([point[0], point[1], 0.0]) / np.linalg.norm(point[:2])
    touch = np.asarray(point, float) + [0, 0, FINGERTIP_CLOSED]
    stroke = (touch + [0, 0, approach], touch - [0, 0, depth])
    rot = None
    for turn in np.radians([0.0, 30.0, -30.0, 60.0, -60.0, 90.0]):
        c, s = math.cos(turn), math.sin(turn)
        closing = [-radial[1] * c - radial[0] * s, radial[0] * c - radial[1] * s, 0.0]
        try:
            rot = top_down_rotation(ctx, side, closing, *stroke)
            break
        except ExpertError:
            continue
    if rot is None:
        raise ExpertError(f"{side} arm cannot press at {np.round(point, 3).tolist()}")
    yield from set_gripper(ctx, side, 0.0, 6)
    yield from arm_goto(ctx, side, stroke[0], rot, gripper=0.0)
    with ctx.precision():
        yield from arm_line(ctx, side, stroke[1], rot, 0.0, speed=0.06)
        yield from hold(ctx, 4)
    yield from arm_line(ctx, side, stroke[0], rot, 0.0, speed=0.1)


def pull_in(ctx: ExpertContext, side: str, radius: float) -> Actions:
    """Pull the TCP (and what it holds) in along the line to the robot's base, to ``radius`` m from
    it, at its height: a long held object swings wide when the torso turns."""
    p, rot = tcp_pose(ctx, side)
    xy = p[:2] * (radius / np.linalg.norm(p[:2]))
    yield from arm_line(ctx, side, [xy[0], xy[1], p[2]], rot, 0.0, speed=0.25)


def hold_aside(
    ctx: ExpertContext, side: str, radius: float = 0.32, off_heading: float = 50.0, speed: float = 0.4
) -> Actions:
    """Move the TCP (and what it holds) to ``radius`` m from the base, ``off_heading`` deg to the
    arm's own side of the torso's heading, at its height: out of the head camera's view while it
    searches (the torso carries the arm along)."""
    p, rot = tcp_pose(ctx, side)
    a = math.radians(90.0 + math.degrees(ctx.yaw) + (off_heading if side == "left" else -off_heading))
    yield from arm_line(ctx, side, [radius * math.cos(a), radius * math.sin(a), p[2]], rot, 0.0, speed=speed)


def strike(
    ctx: ExpertContext, side: str, tool: int, target, above: float = 0.05, depth: float = 0.004
) -> Actions:
    """Bring held tool ``tool``'s head (``functional.tool_head``) down onto the world point ``target``
    (a top surface) from ``above`` m, ``depth`` m past first touch, then back up. The wrist turns the
    tool about the vertical so its head points away from the robot's base (the handle behind it),
    or the nearest turn IK reaches along the stroke."""
    head = ctx.obj(tool).functional.tool_head
    p, rot = tcp_pose(ctx, side)
    pos, obj_rot = ctx.pose(tool)
    bottom = pos + obj_rot @ (np.asarray(head.point) - [0.0, 0.0, head.half[2]])
    to_tcp = p - bottom  # head bottom -> TCP, world
    target = np.asarray(target, float)
    out = math.atan2(target[1], target[0])
    now = math.atan2(-to_tcp[1], -to_tcp[0])  # the direction the head points from the TCP
    base_turn = math.atan2(math.sin(out - now), math.cos(out - now))
    for extra in np.radians([0.0, 20.0, -20.0, 40.0, -40.0, 60.0, -60.0]):
        turn = rot_z(base_turn + extra)
        contact = target + turn @ to_tcp - [0.0, 0.0, depth]
        stroke = (contact + [0.0, 0.0, above], contact)
        try:
            for q_pos in stroke:
                solve_ik(ctx, side, arm_of(ctx.action, side), q_pos, turn @ rot)
        except ExpertError:
            continue
        yield from arm_line(ctx, side, stroke[0], turn @ rot, 0.0, speed=0.25)
        yield from arm_line(ctx, side, stroke[1], turn @ rot, 0.0, speed=0.15)
        yield from hold(ctx, 2)
        yield from arm_line(ctx, side, stroke[0], turn @ rot, 0.0, speed=0.15)
        return
    raise ExpertError(
        f"{side} arm cannot bring the {ctx.objects[tool]}'s head onto {np.round(target, 3).tolist()}"
    )


def carry_and_turn(
    ctx: ExpertContext, side: str, pos, angle: float, speed: float = 0.2, steps_per_rad: int = 12
) -> Actions:
    """Move the TCP in a straight line to ``pos`` while turning it about the vertical by ``angle``
    rad (one smooth motion, as long as the slower of the two)."""
    ctx.intent.camera_mode = CAMERA_HOLD
    p0, rot0 = tcp_pose(ctx, side)
    dist = float(np.linalg.norm(np.asarray(pos) - p0))
    n = max(4, int(math.ceil(dist * math.pi / 2 / (speed * CONTROL_DT))), int(abs(angle) * steps_per_rad))
    q = arm_of(ctx.action, side)
    for k in range(1, n + 1):
        s = 0.5 - 0.5 * math.cos(math.pi * k / n)
        q = solve_ik(
            ctx, side, q, p0 + s * (np.asarray(pos) - p0), rot_z(s * angle) @ rot0, max_step=MAX_PATH_STEP
        )
        ctx.action = with_arm(ctx.action, side, q)
        yield ctx.emit()


def retreat(ctx: ExpertContext, side: str, trailing: bool = False) -> Actions:
    """Return the arm to its home configuration, gripper open. ``trailing``: the arm goes home while
    the script goes on with the head and the other arm (``await_trailing`` waits for it, ``halt``
    stops it)."""
    home = embodiment.home_arm(ctx.sim.info.workspace.two_level)[side]
    if trailing:
        ctx.require_idle(side)
        ctx.trailing[side] = (interpolate_joints(arm_of(ctx.action, side), home, max_vel=1.6), 1.0)
        return
    ctx.intent.camera_mode = CAMERA_HOLD
    yield from move_arm_joint(ctx, side, home, gripper=1.0, max_vel=1.6)


def arm_for(point, then=None) -> str:
    """Left arm for objects on the robot's left half of the fan, right arm otherwise; with a known
    destination ``then``, the side of the midpoint heading of the two."""
    h = heading_deg(point)
    if then is not None:
        h = 0.5 * (h + heading_deg(then))
    return "left" if h >= 90.0 else "right"
