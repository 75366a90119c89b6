"""The room around the robot: four walls and a ceiling (visual only: no contacts, no mass), so that no
view the robot can take shows an empty void, plus a sky gradient behind everything."""

from __future__ import annotations

from dataclasses import dataclass

import mujoco

from ..assets.base import add_geom

ROOM_GROUP = 0  # rendered by default


@dataclass(frozen=True)
class RoomSize:
    """The room's inner faces in world metres (robot base at the origin, facing +y)."""

    x_half: float = 2.6
    y_front: float = 2.8
    y_back: float = -2.0
    height: float = 2.8
    wall_thickness: float = 0.05


ROOM = RoomSize()


def _visual_box(spec: mujoco.MjSpec, name: str, pos, half, material: str) -> None:
    g = add_geom(
        spec.worldbody,
        mujoco.mjtGeom.mjGEOM_BOX,
        half,
        pos,
        (1, 1, 1, 1),
        name=name,
        material=material,
        collide=False,
    )
    g.group = ROOM_GROUP


def add_room(spec: mujoco.MjSpec, wall_material: str, ceiling_material: str, room: RoomSize = ROOM) -> None:
    """Walls on all four sides and a ceiling, inner faces at ``room``'s bounds."""
    t = room.wall_thickness
    cx = 0.0
    cy = 0.5 * (room.y_front + room.y_back)
    hx = room.x_half + t
    hy = 0.5 * (room.y_front - room.y_back) + t
    hz = 0.5 * room.height
    _visual_box(spec, "wall_front", (cx, room.y_front + t, hz), (hx, t, hz), wall_material)
    _visual_box(spec, "wall_back", (cx, room.y_back - t, hz), (hx, t, hz), wall_material)
    _visual_box(spec, "wall_left", (-room.x_half - t, cy, hz), (t, hy, hz), wall_material)
    _visual_box(spec, "wall_right", (room.x_half + t, cy, hz), (t, hy, hz), wall_material)
    _visual_box(spec, "ceiling", (cx, cy, room.height + t), (hx, hy, t), ceiling_material)


def add_sky(spec: mujoco.MjSpec, top=(0.55, 0.65, 0.8), bottom=(0.85, 0.85, 0.82)) -> None:
    """A gradient skybox: what a view past every wall would show (none should, see add_room)."""
    tex = spec.add_texture()
    tex.name = "sky"
    tex.type = mujoco.mjtTexture.mjTEXTURE_SKYBOX
    tex.builtin = mujoco.mjtBuiltin.mjBUILTIN_GRADIENT
    tex.rgb1, tex.rgb2 = top, bottom
    tex.width = tex.height = 64
