"""Scene appearance: floor (background), tabletop, and illumination. ID scenes use the default
look; OOD scenes draw a random one (``random_appearance``)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from PIL import Image, ImageFilter


@dataclass(frozen=True)
class Appearance:
    floor_rgb1: tuple[float, float, float] = (0.42, 0.44, 0.47)
    floor_rgb2: tuple[float, float, float] = (0.36, 0.38, 0.41)
    floor_repeat: float = 8.0
    table_rgba: tuple[float, float, float, float] = (0.62, 0.52, 0.42, 1.0)
    table_texture_seed: int | None = None  # None: plain colour; else a procedural grain texture
    light_dir: tuple[float, float, float] = (-0.2, 0.4, -1.0)
    light_diffuse: float = 0.65
    ambient: float = 0.35


DEFAULT_APPEARANCE = Appearance()


def random_appearance(rng: np.random.Generator) -> Appearance:
    """OOD look: random floor colours and pattern scale, table colour with grain, light intensity
    and direction."""
    base = rng.uniform(0.1, 0.85, 3)
    floor2 = np.clip(base + rng.uniform(-0.25, 0.25, 3), 0, 1)
    table = rng.uniform(0.25, 0.9, 3)
    azimuth = rng.uniform(0, 2 * np.pi)
    tilt = rng.uniform(0.15, 0.8)  # horizontal component of the light direction
    return Appearance(
        floor_rgb1=tuple(map(float, base)),
        floor_rgb2=tuple(map(float, floor2)),
        floor_repeat=float(rng.uniform(3, 14)),
        table_rgba=(*map(float, table), 1.0),
        table_texture_seed=int(rng.integers(0, 2**31 - 1)),
        light_dir=(float(tilt * np.cos(azimuth)), float(tilt * np.sin(azimuth)), -1.0),
        light_diffuse=float(rng.uniform(0.35, 0.95)),
        ambient=float(rng.uniform(0.2, 0.5)),
    )


def table_texture(seed: int, rgb: tuple[float, float, float], size: int = 128) -> np.ndarray:
    """A grain-like texture around ``rgb`` (blurred, stretched noise)."""
    rng = np.random.default_rng(seed)
    noise = rng.normal(0.0, 1.0, (size, size // 4))
    img = Image.fromarray(((noise - noise.min()) / np.ptp(noise) * 255).astype(np.uint8)).resize((size, size))
    grain = np.asarray(img.filter(ImageFilter.GaussianBlur(1.5)), float) / 255.0
    out = np.asarray(rgb, float)[None, None, :] * (0.75 + 0.5 * grain[..., None])
    return (np.clip(out, 0, 1) * 255).astype(np.uint8)
