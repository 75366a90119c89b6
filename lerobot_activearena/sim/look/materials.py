"""Surface materials for the room and the table: a procedural texture, its scale, and a Phong finish
(MuJoCo's classic renderer: RGB texture, specular, shininess; no reflections).

ID scenes draw from a small fixed set (wood tables, tiled floors, plaster walls). OOD scenes draw
from texture families that ID never uses, with random colours and scales.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from ..assets.base import add_texture_material
from .textures import FAMILIES, Rgb, make_texture


@dataclass(frozen=True)
class SurfaceMaterial:
    family: str  # a texture family of textures.FAMILIES
    rgb: Rgb  # base colour, 0-1
    seed: int  # texture seed
    tile_m: float  # metres one texture tile covers
    specular: float = 0.1
    shininess: float = 0.1

    def __post_init__(self):
        if self.family not in FAMILIES:
            raise ValueError(f"unknown texture family {self.family!r}; choose from {sorted(FAMILIES)}")
        if self.tile_m <= 0:
            raise ValueError(f"tile_m must be > 0 m, got {self.tile_m}")


# ---- ID: the fixed set -------------------------------------------------------------------------
ID_MATERIALS: dict[str, tuple[SurfaceMaterial, ...]] = {
    "table": (
        SurfaceMaterial("wood", (0.66, 0.49, 0.31), 11, 0.9, 0.15, 0.2),  # oak
        SurfaceMaterial("wood", (0.45, 0.30, 0.20), 12, 0.9, 0.15, 0.2),  # walnut
    ),
    "floor": (
        SurfaceMaterial("tiles", (0.70, 0.70, 0.68), 21, 1.2, 0.1, 0.15),
        SurfaceMaterial("tiles", (0.74, 0.67, 0.58), 22, 1.2, 0.1, 0.15),
    ),
    "wall": (
        SurfaceMaterial("plaster", (0.86, 0.84, 0.79), 31, 1.5, 0.0, 0.0),
        SurfaceMaterial("plaster", (0.74, 0.80, 0.76), 32, 1.5, 0.0, 0.0),
    ),
}

# ---- OOD: held-out families --------------------------------------------------------------------
# (family, base colour low, base colour high, tile size range m, specular)
OOD_CHOICES: dict[str, tuple[tuple[str, Rgb, Rgb, tuple[float, float], float], ...]] = {
    "table": (
        ("marble", (0.75, 0.75, 0.72), (0.95, 0.95, 0.93), (0.5, 1.2), 0.3),
        ("granite", (0.25, 0.22, 0.2), (0.6, 0.55, 0.5), (0.4, 1.0), 0.25),
        ("terrazzo", (0.7, 0.68, 0.62), (0.9, 0.88, 0.85), (0.5, 1.0), 0.2),
        ("brushed_metal", (0.55, 0.56, 0.58), (0.8, 0.8, 0.82), (0.3, 0.8), 0.4),
        ("fabric", (0.15, 0.15, 0.2), (0.85, 0.8, 0.75), (0.08, 0.2), 0.0),
    ),
    "floor": (
        ("carpet", (0.15, 0.12, 0.12), (0.6, 0.5, 0.45), (0.8, 1.5), 0.0),
        ("concrete", (0.45, 0.45, 0.45), (0.7, 0.7, 0.68), (1.0, 2.0), 0.05),
        ("granite", (0.2, 0.2, 0.2), (0.5, 0.5, 0.5), (0.6, 1.2), 0.2),
        ("terrazzo", (0.55, 0.5, 0.45), (0.85, 0.82, 0.78), (0.8, 1.5), 0.15),
    ),
    "wall": (
        ("brick", (0.45, 0.2, 0.15), (0.75, 0.45, 0.35), (1.0, 2.0), 0.0),
        ("concrete", (0.5, 0.5, 0.5), (0.78, 0.78, 0.76), (1.5, 2.5), 0.0),
        ("fabric", (0.2, 0.15, 0.25), (0.8, 0.75, 0.7), (0.2, 0.5), 0.0),  # curtains
        ("marble", (0.6, 0.6, 0.6), (0.9, 0.9, 0.88), (1.0, 2.0), 0.2),
    ),
}

ROLES = tuple(ID_MATERIALS)


def id_families() -> set[str]:
    return {m.family for ms in ID_MATERIALS.values() for m in ms}


def ood_families() -> set[str]:
    return {c[0] for cs in OOD_CHOICES.values() for c in cs}


def draw_material(role: str, split: str, rng: np.random.Generator) -> SurfaceMaterial:
    """One material for ``role`` (table / floor / wall): ID from the fixed set, OOD from the
    held-out families with a random colour and scale."""
    if role not in ROLES:
        raise ValueError(f"unknown surface role {role!r}; choose from {ROLES}")
    if split == "id":
        options = ID_MATERIALS[role]
        return options[int(rng.integers(len(options)))]
    if split != "ood":
        raise ValueError(f"split must be 'id' or 'ood', got {split!r}")
    family, lo, hi, (t0, t1), specular = OOD_CHOICES[role][int(rng.integers(len(OOD_CHOICES[role])))]
    rgb = tuple(float(v) for v in rng.uniform(lo, hi))
    return SurfaceMaterial(
        family, rgb, int(rng.integers(0, 2**31 - 1)), float(rng.uniform(t0, t1)), specular, 0.2 * specular
    )


def add_surface_material(
    spec: mujoco.MjSpec, name: str, material: SurfaceMaterial, texture_px: int = 256, uniform: bool = True
) -> str:
    """Register the material's texture and a material ``name`` using it. ``uniform``: for primitives,
    texture coordinates uniform in space (one tile covers ``tile_m`` metres on any face); otherwise
    for meshes whose texture coordinates are in metres."""
    rgb = make_texture(material.family, material.seed, material.rgb, texture_px)
    repeat = 1.0 / material.tile_m
    add_texture_material(spec, name, rgb, texrepeat=(repeat, repeat), texuniform=uniform)
    mat = spec.material(name)
    mat.specular = material.specular
    mat.shininess = material.shininess
    mat.reflectance = 0.0
    return name
