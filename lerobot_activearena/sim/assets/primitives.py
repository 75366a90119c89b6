"""Primitive objects: can, block, ball, bottle (free bodies with collision, mass and colour)."""

from __future__ import annotations

import mujoco

from ..look.dress import dress
from . import dressing
from .base import ObjectInfo, add_geom as _geom, free_body as _free_body
from .functional import Functional
from .registry import register_asset


@register_asset("can", footprint=0.035, role="task")
def add_can(
    spec, name, pos, yaw=0.0, radius=0.033, height=0.12, mass=0.3, rgba=(0.75, 0.1, 0.1, 1)
) -> ObjectInfo:
    b = _free_body(spec, name, pos, yaw)
    shell = _geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius, height / 2, 0),
        (0, 0, height / 2),
        rgba,
        mass,
        f"{name}_body",
    )
    lid = _geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius * 0.85, 0.004, 0),
        (0, 0, height + 0.004),
        (0.8, 0.8, 0.82, 1),
        0.0,
    )
    dress(spec, b, name, [shell, lid], dressing.can(spec, name, radius, height, rgba))
    return ObjectInfo(
        name, "can", name, (radius, radius, height / 2 + 0.004), (0, 0, height / 2 + 0.004), mass
    )


@register_asset("block", footprint=0.036, role="task")
def add_block(
    spec, name, pos, yaw=0.0, half=(0.025, 0.025, 0.025), mass=0.1, rgba=(0.2, 0.4, 0.8, 1)
) -> ObjectInfo:
    b = _free_body(spec, name, pos, yaw)
    _geom(b, mujoco.mjtGeom.mjGEOM_BOX, half, (0, 0, half[2]), rgba, mass, f"{name}_body")
    return ObjectInfo(name, "block", name, tuple(half), (0, 0, half[2]), mass)


@register_asset("ball", footprint=0.032, role="distractor")
def add_ball(spec, name, pos, yaw=0.0, radius=0.03, mass=0.05, rgba=(0.9, 0.7, 0.1, 1)) -> ObjectInfo:
    b = _free_body(spec, name, pos, yaw)
    _geom(
        b,
        mujoco.mjtGeom.mjGEOM_SPHERE,
        (radius, 0, 0),
        (0, 0, radius),
        rgba,
        mass,
        f"{name}_body",
        friction=(1.0, 0.01, 0.01),
    )
    return ObjectInfo(name, "ball", name, (radius,) * 3, (0, 0, radius), mass)


@register_asset("bottle", footprint=0.032, role="task")
def add_bottle(
    spec, name, pos, yaw=0.0, radius=0.03, height=0.18, mass=0.25, rgba=(0.2, 0.7, 0.4, 1)
) -> ObjectInfo:
    b = _free_body(spec, name, pos, yaw)
    body_h = height * 0.72
    shell = _geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius, body_h / 2, 0),
        (0, 0, body_h / 2),
        rgba,
        mass * 0.9,
        f"{name}_body",
    )
    neck_h = height - body_h
    neck = _geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius * 0.4, neck_h / 2, 0),
        (0, 0, body_h + neck_h / 2),
        (0.9, 0.9, 0.9, 1),
        mass * 0.1,
    )
    dress(spec, b, name, [shell, neck], dressing.bottle(spec, name, radius, height, body_h, rgba))
    # Held by the neck, just above the shoulder: the palm clears the cap.
    return ObjectInfo(
        name,
        "bottle",
        name,
        (radius, radius, height / 2),
        (0, 0, height / 2),
        mass,
        functional=Functional(grasp=((0.0, 0.0, body_h + 0.03),)),
    )
