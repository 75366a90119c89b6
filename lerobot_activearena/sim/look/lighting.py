"""One key light (directional, optionally shadow-casting) plus ambient. ID scenes share one setup;
OOD scenes draw the direction, colour temperature and intensity from ranges ID never uses."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def kelvin_to_rgb(kelvin: float) -> tuple[float, float, float]:
    """The colour of a black body at ``kelvin`` (1,500-15,000 K) as linear RGB in 0-1, normalised so
    the brightest channel is 1 (a fit of the Planckian locus in sRGB; 6,500 K is near white)."""
    if not 1500 <= kelvin <= 15000:
        raise ValueError(f"colour temperature must be 1500-15000 K, got {kelvin}")
    t = kelvin / 100.0
    if t <= 66:
        r = 255.0
        g = 99.4708025861 * math.log(t) - 161.1195681661
        b = 0.0 if t <= 19 else 138.5177312231 * math.log(t - 10) - 305.0447927307
    else:
        r = 329.698727446 * (t - 60) ** -0.1332047592
        g = 288.1221695283 * (t - 60) ** -0.0755148492
        b = 255.0
    rgb = np.clip(np.array([r, g, b]) / 255.0, 0.0, 1.0)
    return tuple(float(v) for v in rgb / rgb.max())


@dataclass(frozen=True)
class Lighting:
    azimuth_deg: float  # where the light comes from, robot-centric (90 = from straight ahead)
    elevation_deg: float  # above the horizon
    kelvin: float
    intensity: float  # the key light's diffuse strength
    ambient: float

    @property
    def direction(self) -> tuple[float, float, float]:
        """The direction the light travels (from the light towards the scene)."""
        az, el = math.radians(self.azimuth_deg), math.radians(self.elevation_deg)
        return (-math.cos(el) * math.cos(az), -math.cos(el) * math.sin(az), -math.sin(el))

    @property
    def diffuse(self) -> tuple[float, float, float]:
        return tuple(self.intensity * c for c in kelvin_to_rgb(self.kelvin))


# ID: one setup, a neutral light from above, slightly from behind the robot's right shoulder.
ID_LIGHTING = Lighting(azimuth_deg=-60.0, elevation_deg=65.0, kelvin=5500.0, intensity=0.7, ambient=0.35)

# OOD: disjoint from ID in elevation, colour temperature, intensity and ambient; any azimuth.
OOD_ELEVATION_DEG = (25.0, 50.0)
OOD_KELVIN = ((2700.0, 4200.0), (7500.0, 10000.0))  # warm or cold, never ID's neutral
OOD_INTENSITY = ((0.35, 0.55), (0.85, 1.0))  # dimmer or brighter
OOD_AMBIENT = ((0.15, 0.28), (0.42, 0.55))


def draw_lighting(split: str, rng: np.random.Generator) -> Lighting:
    if split == "id":
        return ID_LIGHTING
    if split != "ood":
        raise ValueError(f"split must be 'id' or 'ood', got {split!r}")

    def pick(ranges):
        lo, hi = ranges[int(rng.integers(len(ranges)))]
        return float(rng.uniform(lo, hi))

    return Lighting(
        azimuth_deg=float(rng.uniform(-180.0, 180.0)),
        elevation_deg=float(rng.uniform(*OOD_ELEVATION_DEG)),
        kelvin=pick(OOD_KELVIN),
        intensity=pick(OOD_INTENSITY),
        ambient=pick(OOD_AMBIENT),
    )
