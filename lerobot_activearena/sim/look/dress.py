"""Dressing an object: code-built meshes drawn in place of its primitives, without changing what
physics or perception see.

Physics and perception (the visibility ray casts and their surface samples) use an object's
primitive geoms. Dressing moves the primitives it replaces to ``SHAPE_GROUP`` (hit by rays, not
drawn) and hangs meshes in ``DRESS_GROUP`` (drawn, never hit by rays, no contacts, no mass), each
inside the object's collision extents. So an episode played without pixels is bit-identical
dressed or not; cameras draw ``DRAWN_GROUPS``.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import mujoco
import numpy as np

from .meshes import MeshData, add_visual_mesh

SHAPE_GROUP = 1  # a dressed object's primitives: collide and block rays, not drawn
DRESS_GROUP = 4  # its meshes: drawn only
DRAWN_GROUPS = np.array([1, 0, 1, 0, 1, 0], np.uint8)  # what cameras draw (MjvOption.geomgroup)


@dataclass(frozen=True)
class Dress:
    """One mesh of an object's look, in its body's frame."""

    mesh: MeshData
    rgba: tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)
    pos: tuple[float, float, float] = (0.0, 0.0, 0.0)
    material: str | None = None


def dress(
    spec: mujoco.MjSpec,
    body: mujoco.MjsBody,
    name: str,
    replaces: Iterable[mujoco.MjsGeom],
    parts: list[Dress],
) -> None:
    """Draw ``parts`` on ``body`` instead of the geoms ``replaces`` (which keep colliding and
    blocking rays)."""
    for g in replaces:
        if g.group != 0:
            raise ValueError(f"{name}: geom {g.name!r} is in group {g.group}, not a drawn one (0)")
        g.group = SHAPE_GROUP
    for k, p in enumerate(parts):
        add_visual_mesh(
            spec, body, f"{name}_dress{k}", p.mesh, p.pos, rgba=p.rgba, material=p.material, group=DRESS_GROUP
        )


def scene_option() -> mujoco.MjvOption:
    """The render option every camera of the benchmark uses: dressed looks, no hidden shapes."""
    opt = mujoco.MjvOption()
    opt.geomgroup[:] = DRAWN_GROUPS
    return opt
