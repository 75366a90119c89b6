"""Building blocks the asset builders share: colours from a generator, dressing replaced parts with
meshes, spring-loaded slides and hinges, open boxes, label orientation."""

from __future__ import annotations

import mujoco
import numpy as np

from ..look.dress import dress


def with_alpha(rgb, a=1.0):
    return (*rgb, a)


def dress_parts(spec, name: str, replaced: range | tuple[int, ...], parts) -> None:
    """Dress a ``compound`` object: its parts ``replaced`` (indices) drawn as ``parts`` instead."""
    replaces = [spec.geom(f"{name}_body" if k == 0 else f"{name}_part{k}") for k in replaced]
    dress(spec, spec.body(name), name, replaces, parts)


def random_rgb(rng, lo=0.15, hi=0.9):
    return tuple(float(x) for x in rng.uniform(lo, hi, 3))


def spring_slide(body, name: str, travel: float, stiffness: float, damping: float):
    j = body.add_joint()
    j.name = name
    j.type = mujoco.mjtJoint.mjJNT_SLIDE
    j.axis = (0, 0, 1)
    j.range = (-travel, 0.0)
    j.limited = mujoco.mjtLimited.mjLIMITED_TRUE
    j.stiffness[0] = stiffness
    j.springref = 0.003  # preloaded against the upper limit: rests at exactly 0
    j.damping[0] = damping
    body.gravcomp = 1.0
    return j


def hinge(
    body,
    name: str,
    lo: float,
    hi: float,
    damping: float,
    stiffness: float = 0.0,
    springref: float = 0.0,
    frictionloss: float = 0.0,
):
    """A hinge about the body's y axis limited to [lo, hi] rad."""
    j = body.add_joint()
    j.name, j.type, j.axis = name, mujoco.mjtJoint.mjJNT_HINGE, (0, 1, 0)
    j.range, j.limited = (lo, hi), mujoco.mjtLimited.mjLIMITED_TRUE
    j.damping[0], j.stiffness[0], j.springref, j.frictionloss = damping, stiffness, springref, frictionloss
    return j


def open_box(rgba, inner, wall, height):
    hx, hy = inner[0] / 2 + wall, inner[1] / 2 + wall
    return [
        ("box", (hx, hy, wall / 2), (0, 0, wall / 2), rgba),
        ("box", (wall / 2, hy, height / 2), (hx - wall / 2, 0, height / 2), rgba),
        ("box", (wall / 2, hy, height / 2), (-hx + wall / 2, 0, height / 2), rgba),
        ("box", (hx, wall / 2, height / 2), (0, hy - wall / 2, height / 2), rgba),
        ("box", (hx, wall / 2, height / 2), (0, -hy + wall / 2, height / 2), rgba),
    ]


def label_quat() -> np.ndarray:
    """Rotate the label's texture so the digit reads upright for a viewer on the body's -x side."""
    q = np.zeros(4)
    mujoco.mju_axisAngle2Quat(q, np.array([0.0, 0.0, 1.0]), -np.pi / 2)
    return q
