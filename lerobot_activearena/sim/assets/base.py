"""Building blocks for procedural assets: registered-object info, free bodies, geoms, PIL textures."""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

from ..workspace import WORLD_CONAFFINITY, WORLD_CONTYPE
from .functional import Functional

OBJECT_GROUP = 0


@dataclass
class ObjectInfo:
    """A registered scene object: what visibility, tasks and annotations refer to.

    The body origin is the object's bottom centre; ``half_extents``/``center_offset`` give its
    bounding box in the body frame. ``functional``: where it supports, holds, is grasped, pressed,
    strikes, faces or carries information (typed, validated when built). ``attributes``: what an
    episode drew for it (colours, a number, a date), which instructions and hidden faces report."""

    name: str
    category: str
    body: str = ""
    half_extents: tuple[float, float, float] = (0.0, 0.0, 0.0)
    center_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    mass: float = 0.0
    attributes: dict = field(default_factory=dict)
    functional: Functional = field(default_factory=Functional)


def add_geom(
    body,
    gtype,
    size,
    pos=(0, 0, 0),
    rgba=(0.5, 0.5, 0.5, 1),
    mass=None,
    name=None,
    friction=None,
    quat=None,
    material=None,
    collide: bool = True,
):
    """Add a geom that collides with the world (or a visual-only one with ``collide=False``)."""
    g = body.add_geom()
    if name:
        g.name = name
    g.type = gtype
    sz = np.zeros(3)
    sz[: len(size)] = size
    g.size = sz
    g.pos = np.asarray(pos, float)
    if quat is not None:
        g.quat = np.asarray(quat, float)
    g.rgba = rgba
    if material:
        g.material = material
    g.group = OBJECT_GROUP
    if collide:
        g.contype, g.conaffinity = WORLD_CONTYPE, WORLD_CONAFFINITY
    else:
        g.contype = g.conaffinity = 0
        g.mass = 0.0
    if mass is not None:
        g.mass = mass
    if friction is not None:
        g.friction = friction
    return g


def yaw_quat(yaw: float) -> np.ndarray:
    q = np.zeros(4)
    mujoco.mju_axisAngle2Quat(q, np.array([0.0, 0.0, 1.0]), float(yaw))
    return q


def free_body(spec: mujoco.MjSpec, name: str, pos, yaw: float) -> mujoco.MjsBody:
    """A body with a free joint whose origin (bottom centre) is at ``pos``."""
    body = static_body(spec, name, pos, yaw)
    j = body.add_joint()
    j.name = f"{name}_free"
    j.type = mujoco.mjtJoint.mjJNT_FREE
    j.damping[0] = 0.0005
    return body


def static_body(spec: mujoco.MjSpec, name: str, pos, yaw: float) -> mujoco.MjsBody:
    """A body fixed to the world (pads, mats, button bases)."""
    body = spec.worldbody.add_body()
    body.name = name
    body.pos = np.asarray(pos, float)
    body.quat = yaw_quat(yaw)
    return body


def add_texture_material(
    spec: mujoco.MjSpec,
    name: str,
    rgb: np.ndarray,
    rgba=(1, 1, 1, 1),
    texrepeat=(1, 1),
    texuniform: bool = False,
) -> str:
    """Register an (H, W, 3) uint8 image as a 2D texture with a material of the same name."""
    rgb = np.ascontiguousarray(np.asarray(rgb, dtype=np.uint8))
    if rgb.ndim != 3 or rgb.shape[2] != 3:
        raise ValueError(f"texture {name!r} must be an (H, W, 3) uint8 image, got shape {rgb.shape}")
    tex = spec.add_texture()
    tex.name = name
    tex.type = mujoco.mjtTexture.mjTEXTURE_2D
    tex.width, tex.height = rgb.shape[1], rgb.shape[0]
    tex.nchannel = 3
    tex.data = rgb.tobytes()
    mat = spec.add_material()
    mat.name = name
    mat.textures[mujoco.mjtTextureRole.mjTEXROLE_RGB] = name
    mat.rgba = rgba
    mat.texrepeat = texrepeat
    mat.texuniform = texuniform
    return name
