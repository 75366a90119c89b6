"""Primitive object builders for MjSpec (free bodies with collision, mass and colour).

Each builder adds one body with a free joint; the body's origin is the object's bottom centre so
it can be placed directly on a tabletop. The full asset library of the 35 tasks grows here.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

from .workspace import WORLD_CONAFFINITY, WORLD_CONTYPE

OBJECT_GROUP = 0


@dataclass
class ObjectInfo:
    """A registered scene object: what visibility, tasks and annotations refer to."""

    name: str
    category: str
    body: str = ""
    half_extents: tuple[float, float, float] = (0.0, 0.0, 0.0)  # bounding box, body frame
    center_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)  # bbox centre in the body frame
    mass: float = 0.0
    extra: dict = field(default_factory=dict)


def _geom(body, gtype, size, pos=(0, 0, 0), rgba=(0.5, 0.5, 0.5, 1), mass=None, name=None, friction=None):
    g = body.add_geom()
    if name:
        g.name = name
    g.type = gtype
    g.size = np.asarray(size, float)
    g.pos = np.asarray(pos, float)
    g.rgba = rgba
    g.contype, g.conaffinity, g.group = WORLD_CONTYPE, WORLD_CONAFFINITY, OBJECT_GROUP
    if mass is not None:
        g.mass = mass
    if friction is not None:
        g.friction = friction
    return g


def _free_body(spec: mujoco.MjSpec, name: str, pos, yaw: float) -> mujoco.MjsBody:
    body = spec.worldbody.add_body()
    body.name = name
    body.pos = np.asarray(pos, float)
    q = np.zeros(4)
    mujoco.mju_axisAngle2Quat(q, np.array([0.0, 0.0, 1.0]), float(yaw))
    body.quat = q
    j = body.add_joint()
    j.name = f"{name}_free"
    j.type = mujoco.mjtJoint.mjJNT_FREE
    j.damping[0] = 0.0005
    return body


def add_can(spec, name, pos, yaw=0.0, radius=0.033, height=0.12, mass=0.3, rgba=(0.75, 0.1, 0.1, 1)) -> ObjectInfo:
    b = _free_body(spec, name, pos, yaw)
    _geom(b, mujoco.mjtGeom.mjGEOM_CYLINDER, (radius, height / 2, 0), (0, 0, height / 2), rgba, mass, f"{name}_body")
    _geom(b, mujoco.mjtGeom.mjGEOM_CYLINDER, (radius * 0.85, 0.004, 0), (0, 0, height + 0.004), (0.8, 0.8, 0.82, 1), 0.0)
    return ObjectInfo(name, "can", name, (radius, radius, height / 2 + 0.004), (0, 0, height / 2 + 0.004), mass)


def add_block(spec, name, pos, yaw=0.0, half=(0.025, 0.025, 0.025), mass=0.1, rgba=(0.2, 0.4, 0.8, 1)) -> ObjectInfo:
    b = _free_body(spec, name, pos, yaw)
    _geom(b, mujoco.mjtGeom.mjGEOM_BOX, half, (0, 0, half[2]), rgba, mass, f"{name}_body")
    return ObjectInfo(name, "block", name, tuple(half), (0, 0, half[2]), mass)


def add_ball(spec, name, pos, yaw=0.0, radius=0.03, mass=0.05, rgba=(0.9, 0.7, 0.1, 1)) -> ObjectInfo:
    b = _free_body(spec, name, pos, yaw)
    _geom(b, mujoco.mjtGeom.mjGEOM_SPHERE, (radius, 0, 0), (0, 0, radius), rgba, mass, f"{name}_body",
          friction=(1.0, 0.01, 0.01))
    return ObjectInfo(name, "ball", name, (radius,) * 3, (0, 0, radius), mass)


def add_bottle(spec, name, pos, yaw=0.0, radius=0.03, height=0.18, mass=0.25, rgba=(0.2, 0.7, 0.4, 1)) -> ObjectInfo:
    b = _free_body(spec, name, pos, yaw)
    body_h = height * 0.72
    _geom(b, mujoco.mjtGeom.mjGEOM_CYLINDER, (radius, body_h / 2, 0), (0, 0, body_h / 2), rgba, mass * 0.9, f"{name}_body")
    neck_h = height - body_h
    _geom(b, mujoco.mjtGeom.mjGEOM_CYLINDER, (radius * 0.4, neck_h / 2, 0), (0, 0, body_h + neck_h / 2),
          (0.9, 0.9, 0.9, 1), mass * 0.1)
    return ObjectInfo(name, "bottle", name, (radius, radius, height / 2), (0, 0, height / 2), mass)


OBJECT_BUILDERS = {"can": add_can, "block": add_block, "ball": add_ball, "bottle": add_bottle}
