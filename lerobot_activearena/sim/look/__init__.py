"""How a scene looks (appearance only, never physics): the table, floor and wall materials, the
room, and the light. ``draw_look(split, rng)`` gives ID scenes one of a small fixed set and OOD
scenes held-out texture families, backgrounds and lighting."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .lighting import ID_LIGHTING, Lighting, draw_lighting
from .materials import ID_MATERIALS, SurfaceMaterial, draw_material

CEILING = SurfaceMaterial("plaster", (0.93, 0.92, 0.9), 41, 2.0, 0.0, 0.0)  # every scene's


@dataclass(frozen=True)
class Look:
    table: SurfaceMaterial
    floor: SurfaceMaterial
    wall: SurfaceMaterial
    lighting: Lighting


DEFAULT_LOOK = Look(ID_MATERIALS["table"][0], ID_MATERIALS["floor"][0], ID_MATERIALS["wall"][0], ID_LIGHTING)


def draw_look(split: str, rng: np.random.Generator) -> Look:
    return Look(
        table=draw_material("table", split, rng),
        floor=draw_material("floor", split, rng),
        wall=draw_material("wall", split, rng),
        lighting=draw_lighting(split, rng),
    )


__all__ = ["CEILING", "DEFAULT_LOOK", "Look", "draw_look"]
