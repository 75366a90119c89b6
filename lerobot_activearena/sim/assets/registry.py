"""The asset registry: every object category a scene can contain, with what samplers need to know.

Each category maps to a builder ``build(spec, name, pos, yaw=0.0, **params) -> ObjectInfo`` that adds
one object whose origin (bottom centre) is at ``pos``, plus:

- ``footprint``: radius (m) of a disc covering the object's table footprint (non-overlap placement);
- ``role``: ``"task"`` if some benchmark task names the category, else ``"distractor"``
  (ID scenes draw clutter only from distractors; OOD scenes draw from both);
- ``family``: near-duplicate group (e.g. cup and mug); OOD clutter never adds an object whose
  family is already in the scene;
- ``randomize(rng) -> dict``: optional attribute randomisation (colours, sizes) as builder params.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import mujoco
import numpy as np

from .base import ObjectInfo

ROLES = ("task", "distractor")


@dataclass(frozen=True)
class AssetEntry:
    category: str
    build: Callable[..., ObjectInfo]
    footprint: float
    role: str
    family: str
    randomize: Callable[[np.random.Generator], dict] | None = None
    static: bool = False  # fixed to the world (pads, mats, buttons)


ASSETS: dict[str, AssetEntry] = {}


def register_asset(
    category: str,
    footprint: float,
    role: str,
    family: str | None = None,
    randomize: Callable[[np.random.Generator], dict] | None = None,
    static: bool = False,
):
    """Decorator registering a builder under ``category``."""
    if role not in ROLES:
        raise ValueError(f"asset role must be one of {ROLES}, got {role!r}")

    def deco(fn):
        if category in ASSETS:
            raise ValueError(f"asset category {category!r} is registered twice")
        ASSETS[category] = AssetEntry(
            category, fn, float(footprint), role, family or category, randomize, static
        )
        return fn

    return deco


def build_asset(
    spec: mujoco.MjSpec,
    category: str,
    name: str,
    pos,
    yaw: float = 0.0,
    rng: np.random.Generator | None = None,
    **params,
) -> ObjectInfo:
    """Add one object of ``category``; with ``rng`` its attributes are randomised (explicit
    ``params`` win over randomised ones)."""
    if category not in ASSETS:
        raise ValueError(f"unknown asset category {category!r}; known: {sorted(ASSETS)}")
    entry = ASSETS[category]
    if rng is not None and entry.randomize is not None:
        params = {**entry.randomize(rng), **params}
    info = entry.build(spec, name, np.asarray(pos, float), yaw, **params)
    info.category = category
    info.functional.validate(f"asset {category!r} ({name})", info.half_extents, info.center_offset)
    return info


def categories(role: str | None = None) -> list[str]:
    return sorted(c for c, e in ASSETS.items() if role is None or e.role == role)
