"""Named predicates over the simulator state that success checks compose. One rule for arguments:

- a predicate about one body (its pose: ``upright``, ``in_place`` ...; its contacts:
  ``touched_by_robot``, ``released``, ``pressed_by`` ...) takes the body's name;
- a relation between objects (``resting_on``, ``inside_disc``, ``left_of``, ``on_support``,
  ``in_container``, ``stacked_on``, ``beside``, ``facing``, ``touching``, ``struck``) and anything
  that needs an object's shape takes its ``ObjectInfo`` (``scene.obj(name)``) and reads the typed
  functional metadata (a support's top and half sizes, a container's floor and rim).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from ..sim import embodiment
from ..sim.action import LEFT_GRIPPER, RIGHT_GRIPPER
from ..sim.assets.base import ObjectInfo
from ..sim.embodiment import ARMS
from ..sim.simulator import ActiveArenaSim
from ..sim.workspace import TABLE_TOP

GRIPPER_CLOSED_BELOW = 0.3  # normalised gripper state (0 closed, 1 open)


def polar(xy) -> tuple[float, float]:
    """(distance from the robot base, workspace angle in degrees)."""
    return float(np.hypot(xy[0], xy[1])), math.degrees(math.atan2(xy[1], xy[0]))


def position(sim: ActiveArenaSim, body: str) -> np.ndarray:
    return sim.data.body(body).xpos.copy()


def joint_pos(sim: ActiveArenaSim, joint: str) -> float:
    return float(sim.data.joint(joint).qpos[0])


def upright(sim: ActiveArenaSim, body: str, max_tilt_deg: float = 15.0) -> bool:
    z = sim.data.body(body).xmat.reshape(3, 3)[:, 2]
    return bool(z[2] >= math.cos(math.radians(max_tilt_deg)))


def on_a_face(sim: ActiveArenaSim, body: str, max_tilt_deg: float = 15.0) -> bool:
    """Resting on one of its box faces (any of the body's axes vertical): a block set down on its side."""
    rot = sim.data.body(body).xmat.reshape(3, 3)
    return bool(np.abs(rot[2]).max() >= math.cos(math.radians(max_tilt_deg)))


def knocked_over(sim: ActiveArenaSim, body: str, tilt_deg: float = 45.0) -> bool:
    return not upright(sim, body, tilt_deg)


def in_place(sim: ActiveArenaSim, body: str, tol: float = 0.03) -> bool:
    """Within ``tol`` m (horizontally) of where it was spawned."""
    spawn = sim.model.body(body).pos
    return bool(np.linalg.norm(sim.data.body(body).xpos[:2] - spawn[:2]) <= tol)


def is_free(sim: ActiveArenaSim, body: str) -> bool:
    """Whether ``body`` moves freely (a free joint), i.e. is not welded to the world."""
    m = sim.model
    b = m.body(body)
    return bool(b.jntnum[0] > 0 and m.jnt_type[b.jntadr[0]] == 0)


def off_table(sim: ActiveArenaSim, body: str, below: float = 0.05) -> bool:
    """Fallen below the tabletop (``below`` m under it) or out of the fan's outer radius."""
    p = sim.data.body(body).xpos
    return bool(p[2] < TABLE_TOP - below or np.hypot(p[0], p[1]) > 1.12)


def lifted(sim: ActiveArenaSim, body: str, height: float) -> bool:
    """Raised at least ``height`` m above its spawn height."""
    return bool(sim.data.body(body).xpos[2] - sim.model.body(body).pos[2] >= height)


def _robot_body(sim: ActiveArenaSim, bid: int) -> bool:
    return sim.model.body(bid).name.startswith(embodiment.PREFIX)


def _gripper_body(sim: ActiveArenaSim, bid: int, arm: str) -> bool:
    return sim.model.body(bid).name.startswith(f"{embodiment.PREFIX}gripper_{arm}")


def contacts_with(sim: ActiveArenaSim, body: str):
    """(other body id, contact position) of every contact of the geoms of ``body`` and of the bodies
    attached to it (a bell's plunger, a button's cap)."""
    m, d = sim.model, sim.data
    root = m.body_rootid[m.body(body).id]
    bodies = m.geom_bodyid[d.contact.geom]  # (ncon, 2); the contact list's arrays, not its structs
    mine = m.body_rootid[bodies] == root
    first, second = mine[:, 0] & ~mine[:, 1], mine[:, 1] & ~mine[:, 0]
    pos = d.contact.pos
    for i in np.flatnonzero(first | second):
        yield int(bodies[i, 1] if first[i] else bodies[i, 0]), pos[i].copy()


def touched_by_robot(sim: ActiveArenaSim, body: str) -> bool:
    return any(_robot_body(sim, other) for other, _ in contacts_with(sim, body))


def released(sim: ActiveArenaSim, body: str) -> bool:
    """No robot link touches it (it rests by itself)."""
    return not touched_by_robot(sim, body)


def held_by_gripper(sim: ActiveArenaSim, body: str) -> str | None:
    """The arm whose gripper holds ``body`` up: it touches that gripper and nothing but the robot
    (no table, no other object under it); None when it is not held."""
    arm = None
    for other, _ in contacts_with(sim, body):
        if not _robot_body(sim, other):
            return None
        for side in ARMS:
            if _gripper_body(sim, other, side):
                arm = side
    return arm


def grasped_by(sim: ActiveArenaSim, body: str, arm: str) -> bool:
    """Both finger pads of ``arm``'s gripper touch ``body`` (or a part attached to it): in that hand,
    even while it also touches something else (a tool striking)."""
    m, d = sim.model, sim.data
    root, prefix = m.body_rootid[m.body(body).id], f"{embodiment.PREFIX}gripper_{arm}_pad_"
    pads = set()
    for c in d.contact[: d.ncon]:
        for pad, other in ((c.geom1, c.geom2), (c.geom2, c.geom1)):
            if m.body_rootid[m.geom_bodyid[other]] == root and m.geom(pad).name.startswith(prefix):
                pads.add(m.geom(pad).name[-1])
    return pads == {"L", "R"}


def gripper_closed(sim: ActiveArenaSim, arm: str) -> bool:
    g = LEFT_GRIPPER if arm == "left" else RIGHT_GRIPPER
    return bool(sim.state()[g] < GRIPPER_CLOSED_BELOW)


TOUCH_DISTANCE = (
    0.002  # m: geoms this close count as touching (a pressing pad flickers in and out of contact)
)


def _collision_geoms(sim: ActiveArenaSim, pred) -> list[int]:
    m = sim.model
    return [
        g
        for g in range(m.ngeom)
        if (m.geom_contype[g] or m.geom_conaffinity[g]) and pred(int(m.geom_bodyid[g]))
    ]


def gripper_contact_near(
    sim: ActiveArenaSim, arm: str, body: str, point, radius_xy: float, radius_z: float
) -> bool:
    """``arm``'s gripper touches ``body`` (or a part attached to it) within the cylinder (radius_xy,
    +/- radius_z) around the world ``point``. Touching = geom distance below ``TOUCH_DISTANCE``
    (``mj_geomDistance``), so a press is seen even at a physics substep without an active contact."""
    m, d = sim.model, sim.data
    key = ("gripper_contact_geoms", arm, body)
    cache = sim.__dict__.setdefault("_predicate_cache", {})
    if key not in cache:
        root = m.body_rootid[m.body(body).id]
        cache[key] = (
            _collision_geoms(sim, lambda b: _gripper_body(sim, b, arm)),
            _collision_geoms(sim, lambda b: m.body_rootid[b] == root),
        )
    grippers, parts = cache[key]
    point = np.asarray(point, float)
    fromto = np.zeros(6)
    for g1 in grippers:
        for g2 in parts:
            if mujoco.mj_geomDistance(m, d, g1, g2, 0.01, fromto) <= TOUCH_DISTANCE:
                pos = 0.5 * (fromto[:3] + fromto[3:])
                if np.hypot(*(pos[:2] - point[:2])) <= radius_xy and abs(pos[2] - point[2]) <= radius_z:
                    return True
    return False


def tcp_on_axis(sim: ActiveArenaSim, arm: str, body: str, radius: float) -> bool:
    """``arm``'s tool centre is within ``radius`` of ``body``'s vertical axis (in the body's frame, so
    a tilted object is measured along its own axis): a grasp centred on it."""
    b = sim.data.body(body)
    local = b.xmat.reshape(3, 3).T @ (sim.data.site(embodiment.TCP_SITES[arm]).xpos - b.xpos)
    return bool(np.hypot(local[0], local[1]) <= radius)


def tcp_over(sim: ActiveArenaSim, arm: str, point, radius_xy: float) -> bool:
    """``arm``'s tool centre (between the fingertips) is within ``radius_xy`` of ``point``, horizontally."""
    tcp = sim.data.site(embodiment.TCP_SITES[arm]).xpos
    return bool(np.hypot(*(tcp[:2] - np.asarray(point, float)[:2])) <= radius_xy)


def pressed_by(
    sim: ActiveArenaSim,
    arm: str,
    body: str,
    point,
    radius_xy: float = 0.025,
    radius_z: float = 0.03,
    centered_within: float | None = None,
) -> bool:
    """``arm``'s closed gripper touches ``body`` near ``point`` (the paper's release: closed gripper,
    contact within 2.5 cm (xy) / 3 cm (z) of the press point); with ``centered_within``, its tool
    centre must also be that close to the point horizontally (a press *at* the point)."""
    if centered_within is not None and not tcp_over(sim, arm, point, centered_within):
        return False
    return gripper_closed(sim, arm) and gripper_contact_near(sim, arm, body, point, radius_xy, radius_z)


def pressed_by_either(
    sim: ActiveArenaSim, body: str, point, radius_xy: float = 0.025, radius_z: float = 0.03
) -> bool:
    return any(pressed_by(sim, arm, body, point, radius_xy, radius_z) for arm in ARMS)


def body_point(sim: ActiveArenaSim, body: str, local) -> np.ndarray:
    """World position of a point given in ``body``'s frame."""
    b = sim.data.body(body)
    return b.xpos + b.xmat.reshape(3, 3) @ np.asarray(local, float)


def press_point(sim: ActiveArenaSim, obj: ObjectInfo) -> np.ndarray:
    """World position of ``obj``'s press point (``functional.press``), on its moving part if any."""
    press = obj.functional.press
    return body_point(sim, press.body or obj.body, press.point)


def press_moved(sim: ActiveArenaSim, obj: ObjectInfo) -> bool:
    """``obj``'s pressed part (plunger, cap, stapler arm, rocker) has travelled past its press
    threshold (who pressed it is for ``pressed_by`` to say)."""
    press = obj.functional.press
    return press.is_pressed(joint_pos(sim, press.joint))


# ---- placement relations on typed functional metadata -------------------------------------------
def resting_on(
    sim: ActiveArenaSim,
    obj: ObjectInfo,
    support: ObjectInfo,
    margin: float = 0.01,
    z_tol: float = 0.012,
    half_xy=None,
) -> bool:
    """``obj``'s origin (its bottom centre) lies over ``support``'s top rectangle (its
    ``functional.support`` half sizes, or ``half_xy``, in the support's frame, shrunk by ``margin``)
    at the top's height (+/- ``z_tol``). Where the object's whole footprint matters: ``on_support``."""
    top = support.functional.support
    if top is None:
        raise ValueError(f"{support.name} ({support.category}) declares no support surface")
    s = sim.data.body(support.name)
    local = s.xmat.reshape(3, 3).T @ (sim.data.body(obj.name).xpos - s.xpos)
    half = top.half if half_xy is None else half_xy
    hx, hy = (half, half) if np.isscalar(half) else half
    return bool(
        abs(local[0]) <= hx - margin and abs(local[1]) <= hy - margin and abs(local[2] - top.top) <= z_tol
    )


def inside_disc(sim: ActiveArenaSim, obj: ObjectInfo, centre: ObjectInfo, radius: float) -> bool:
    """Horizontal distance between the two objects' origins below ``radius``."""
    a, b = sim.data.body(obj.name).xpos, sim.data.body(centre.name).xpos
    return bool(np.linalg.norm(a[:2] - b[:2]) <= radius)


def left_of(sim: ActiveArenaSim, a: ObjectInfo, b: ObjectInfo, min_deg: float = 0.0) -> bool:
    """``a`` is left of ``b`` as the robot sees them (larger workspace angle)."""
    return polar(sim.data.body(a.name).xpos)[1] - polar(sim.data.body(b.name).xpos)[1] > min_deg


def right_of(sim: ActiveArenaSim, a: ObjectInfo, b: ObjectInfo, min_deg: float = 0.0) -> bool:
    return left_of(sim, b, a, min_deg)


FOOTPRINT_GRID = 5  # points per side sampled over an object's footprint


def _pose(sim: ActiveArenaSim, obj: ObjectInfo) -> tuple[np.ndarray, np.ndarray]:
    b = sim.data.body(obj.body)
    return b.xpos.copy(), b.xmat.reshape(3, 3).copy()


def _local(sim: ActiveArenaSim, frame: ObjectInfo, points) -> np.ndarray:
    """World points in ``frame``'s body frame."""
    pos, rot = _pose(sim, frame)
    return (np.atleast_2d(points) - pos) @ rot


def footprint_points(
    sim: ActiveArenaSim, obj: ObjectInfo, n: int = FOOTPRINT_GRID, lowest_face: bool = False
) -> np.ndarray:
    """World points on an n x n grid over the base of ``obj``'s bounding box; with ``lowest_face``,
    over whichever face of the box points down now (a cube set down on its side)."""
    half, centre = np.asarray(obj.half_extents, float), np.asarray(obj.center_offset, float)
    pos, rot = _pose(sim, obj)
    axis, sign = 2, -1.0  # the body's -z face
    if lowest_face:
        axis = int(np.argmax(np.abs(rot[2])))
        sign = -float(np.sign(rot[2, axis]))
    a, b = [k for k in range(3) if k != axis]
    u = np.linspace(-1.0, 1.0, n)
    ga, gb = np.meshgrid(centre[a] + u * half[a], centre[b] + u * half[b])
    local = np.empty((ga.size, 3))
    local[:, a], local[:, b] = ga.ravel(), gb.ravel()
    local[:, axis] = centre[axis] + sign * half[axis]
    return pos + local @ rot.T


def lowest_z(sim: ActiveArenaSim, obj: ObjectInfo) -> float:
    """Height of the lowest point of ``obj``'s collision geoms (exact for boxes, spheres, cylinders
    and capsules, whichever way they lie: its bounding box overshoots below a rolled can)."""
    m, d = sim.model, sim.data
    body = m.body(obj.body).id
    low = math.inf
    for g in np.flatnonzero(m.geom_bodyid == body):
        if m.geom_contype[g] == 0 and m.geom_conaffinity[g] == 0:
            continue  # visual only
        t, size = int(m.geom_type[g]), m.geom_size[g]
        z, rz = d.geom_xpos[g][2], d.geom_xmat[g].reshape(3, 3)[2]  # rz: the world z row
        if t == mujoco.mjtGeom.mjGEOM_BOX:
            drop = np.abs(rz) @ size
        elif t == mujoco.mjtGeom.mjGEOM_SPHERE:
            drop = size[0]
        elif t in (mujoco.mjtGeom.mjGEOM_CYLINDER, mujoco.mjtGeom.mjGEOM_CAPSULE):
            a = abs(rz[2])  # the axis' vertical component
            rim = size[0] if t == mujoco.mjtGeom.mjGEOM_CAPSULE else size[0] * math.sqrt(max(0.0, 1 - a * a))
            drop = size[1] * a + rim
        elif t == mujoco.mjtGeom.mjGEOM_MESH:
            adr, n = m.mesh_vertadr[m.geom_dataid[g]], m.mesh_vertnum[m.geom_dataid[g]]
            drop = -float((m.mesh_vert[adr : adr + n] @ rz).min())
        else:  # ellipsoid and the rest: their bounding box
            drop = np.abs(rz) @ size
        low = min(low, float(z - drop))
    if low == math.inf:
        raise ValueError(f"{obj.name} has no collision geoms on body {obj.body}")
    return low


def centre_point(sim: ActiveArenaSim, obj: ObjectInfo) -> np.ndarray:
    """World centre of ``obj``'s bounding box."""
    return body_point(sim, obj.body, obj.center_offset)


def bottom_z(sim: ActiveArenaSim, obj: ObjectInfo) -> float:
    """Height of the lowest point of ``obj``'s bounding box, whichever way it lies."""
    _, rot = _pose(sim, obj)
    return float(centre_point(sim, obj)[2] - np.abs(rot[2]) @ np.asarray(obj.half_extents, float))


def top_point(sim: ActiveArenaSim, obj: ObjectInfo) -> np.ndarray:
    """World centre of the top of ``obj``'s bounding box (upright)."""
    return centre_point(sim, obj) + [0.0, 0.0, obj.half_extents[2]]


def _over_top(local_xy: np.ndarray, support, margin: float) -> np.ndarray:
    if support.shape == "disc":
        return np.hypot(local_xy[:, 0], local_xy[:, 1]) <= support.half[0] - margin
    return (np.abs(local_xy[:, 0]) <= support.half[0] - margin) & (
        np.abs(local_xy[:, 1]) <= support.half[1] - margin
    )


def on_support(
    sim: ActiveArenaSim,
    obj: ObjectInfo,
    support: ObjectInfo,
    min_overlap: float = 0.5,
    margin: float = 0.0,
    z_tol: float = 0.012,
    any_face: bool = False,
) -> bool:
    """``obj`` rests on ``support``'s top surface (``functional.support``, box or disc): its base at
    the top's height (+/- ``z_tol``), its centre over the top and at least ``min_overlap`` of its
    footprint over it (the top shrunk by ``margin``). Not a fixed radius: a large object half off
    a small mat does not count. ``any_face``: the base is whichever face points down (a block)."""
    top = support.functional.support
    if top is None:
        raise ValueError(f"{support.name} ({support.category}) declares no support surface")
    base = _local(sim, support, footprint_points(sim, obj, lowest_face=any_face))
    centre = _local(sim, support, centre_point(sim, obj))
    if abs(base[:, 2].mean() - top.top) > z_tol:
        return False
    return bool(
        _over_top(centre[:, :2], top, margin)[0] and _over_top(base[:, :2], top, margin).mean() >= min_overlap
    )


def in_container(
    sim: ActiveArenaSim, obj: ObjectInfo, container: ObjectInfo, z_tol: float = 0.01, any_face: bool = False
) -> bool:
    """``obj`` is inside ``container`` (``functional.container``): its centre over the inner floor,
    its base above the floor (- ``z_tol``) and below the rim (inside, not lying across the top).
    ``any_face``: the base is the object's lowest point, whichever way it lies (a can on its side)."""
    box = container.functional.container
    if box is None:
        raise ValueError(f"{container.name} ({container.category}) declares no container")
    c = _local(sim, container, centre_point(sim, obj))[0]
    if any_face:
        low = centre_point(sim, obj).copy()
        low[2] = lowest_z(sim, obj)
        base = _local(sim, container, low)[0, 2]
    else:
        base = _local(sim, container, footprint_points(sim, obj))[:, 2].min()
    inside = abs(c[0]) <= box.inner_half[0] and abs(c[1]) <= box.inner_half[1]
    return bool(inside and box.floor - z_tol <= base < box.rim)


def stacked_on(
    sim: ActiveArenaSim, upper: ObjectInfo, lower: ObjectInfo, xy_tol: float = 0.025, z_tol: float = 0.012
) -> bool:
    """``upper`` sits on top of ``lower``: centres within ``xy_tol`` horizontally and ``upper``'s base
    at ``lower``'s top height (+/- ``z_tol``)."""
    c_up, top = centre_point(sim, upper), top_point(sim, lower)
    base = footprint_points(sim, upper)[:, 2].mean()
    return bool(np.hypot(*(c_up[:2] - top[:2])) <= xy_tol and abs(base - top[2]) <= z_tol)


def beside(
    sim: ActiveArenaSim,
    a: ObjectInfo,
    b: ObjectInfo,
    side: str,
    gap: tuple[float, float] = (0.08, 0.20),
    max_radial: float = 0.08,
) -> bool:
    """``a`` is on ``side`` ('left' / 'right', as the robot sees them: angular order about its base)
    of ``b``: centres ``gap`` m apart (min, max) and within ``max_radial`` m of the same distance
    from the base."""
    if side not in ARMS:
        raise ValueError(f"side must be 'left' or 'right', got {side!r}")
    pa, pb = centre_point(sim, a), centre_point(sim, b)
    (ra, ta), (rb, tb) = polar(pa), polar(pb)
    order = ta > tb if side == "left" else ta < tb
    return bool(order and gap[0] <= np.hypot(*(pa[:2] - pb[:2])) <= gap[1] and abs(ra - rb) < max_radial)


def facing(sim: ActiveArenaSim, obj: ObjectInfo, direction=None, tol_deg: float = 30.0) -> bool:
    """``obj``'s front (``functional.front``) points along the horizontal ``direction`` within
    ``tol_deg``; ``direction=None``: towards the robot's base."""
    front = obj.functional.front
    if front is None:
        raise ValueError(f"{obj.name} ({obj.category}) declares no front")
    pos, rot = _pose(sim, obj)
    f = (rot @ np.asarray(front, float))[:2]
    d = -pos[:2] if direction is None else np.asarray(direction, float)[:2]
    cos = f @ d / (np.linalg.norm(f) * np.linalg.norm(d) + 1e-12)
    return bool(cos >= math.cos(math.radians(tol_deg)))


def touching(sim: ActiveArenaSim, a: ObjectInfo, b: ObjectInfo) -> bool:
    """Some geom of ``a`` (or a part attached to it) is in contact with ``b``."""
    root = sim.model.body_rootid[sim.model.body(b.body).id]
    return any(sim.model.body_rootid[other] == root for other, _ in contacts_with(sim, a.body))


def struck(sim: ActiveArenaSim, tool: ObjectInfo, target: ObjectInfo, radius_xy: float = 0.02) -> bool:
    """``tool``'s head (``functional.tool_head``) touches ``target`` over its top, its centre within
    ``radius_xy`` of the top centre horizontally. Momentary: a task latches it with
    ``monitor.event("struck", ...)`` (and adds who held the tool)."""
    head = tool.functional.tool_head
    if head is None:
        raise ValueError(f"{tool.name} ({tool.category}) declares no tool head")
    centre = body_point(sim, tool.body, head.point)
    top = top_point(sim, target)
    over = np.hypot(*(centre[:2] - top[:2])) <= radius_xy and centre[2] >= top[2]
    return bool(over and touching(sim, tool, target))
