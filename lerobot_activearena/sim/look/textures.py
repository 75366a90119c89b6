"""Procedural surface textures made by code (numpy): wood, marble, granite, tiles, fabric, plaster,
brushed metal, plastic, cardboard, brick, terrazzo, carpet, concrete.

Every texture is a seamless tile (the noise is synthesised in the Fourier domain, so it is periodic;
patterns use whole periods per tile), so a material can repeat it over a table or a wall without
visible seams. The same (family, seed, base colour) always gives the same pixels.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache

import numpy as np

Rgb = tuple[float, float, float]


def periodic_noise(
    rng: np.random.Generator, size: int, beta: float = 2.0, stretch: tuple[float, float] = (1.0, 1.0)
) -> np.ndarray:
    """Seamless fractal noise in [0, 1]: white noise filtered by 1 / f^(beta/2) in the Fourier domain.
    ``stretch`` (sy, sx) > 1 elongates the features along that axis (wood grain, brushed metal)."""
    fy = np.fft.fftfreq(size)[:, None] * stretch[0]
    fx = np.fft.fftfreq(size)[None, :] * stretch[1]
    f = np.sqrt(fx**2 + fy**2)
    f[0, 0] = 1.0
    spectrum = np.fft.fft2(rng.normal(size=(size, size))) / f ** (beta / 2.0)
    spectrum[0, 0] = 0.0
    out = np.fft.ifft2(spectrum).real
    return (out - out.min()) / max(float(np.ptp(out)), 1e-12)


def _grid(size: int) -> tuple[np.ndarray, np.ndarray]:
    """Pixel-centre coordinates (y, x) in [0, 1) of one tile."""
    t = (np.arange(size) + 0.5) / size
    return np.meshgrid(t, t, indexing="ij")


def _mix(a: Rgb, b: Rgb, w: np.ndarray) -> np.ndarray:
    """Per-pixel blend of two colours by a weight map in [0, 1]: (H, W, 3) floats."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return a + (b - a) * np.clip(w, 0, 1)[..., None]


def _shade(rgb: Rgb, factor: float) -> Rgb:
    return tuple(float(np.clip(c * factor, 0, 1)) for c in rgb)


def wood(rng, size, rgb):
    """Growth rings along the tile's length, bent by low-frequency noise, with fine grain."""
    y, _ = _grid(size)
    warp = periodic_noise(rng, size, beta=3.0, stretch=(1.0, 6.0))
    rings = 0.5 + 0.5 * np.sin(2 * np.pi * (int(rng.integers(5, 10)) * y + 2.0 * warp))
    grain = periodic_noise(rng, size, beta=1.2, stretch=(1.0, 12.0))
    return _mix(_shade(rgb, 1.15), _shade(rgb, 0.7), 0.65 * rings**3 + 0.35 * grain)


def marble(rng, size, rgb):
    """A light base with soft dark veins: thin level sets of smooth turbulent noise."""
    y, x = _grid(size)
    turb = periodic_noise(rng, size, beta=4.5)
    phase = 2 * np.pi * (2 * x + y + 1.5 * turb)
    veins = np.exp(-((np.sin(phase) / 0.12) ** 2))
    cloud = periodic_noise(rng, size, beta=2.0)
    return _mix(_shade(rgb, 1.05), _shade(rgb, 0.5), 0.75 * veins + 0.15 * cloud)


def granite(rng, size, rgb):
    """Speckled stone: coarse mottling and dark and light grains."""
    base = periodic_noise(rng, size, beta=2.0)
    speck = rng.random((size, size))
    w = 0.5 + 0.3 * (base - 0.5)
    w = np.where(speck < 0.07, 0.0, np.where(speck > 0.95, 1.0, w))
    return _mix(_shade(rgb, 0.45), _shade(rgb, 1.2), w)


def tiles(rng, size, rgb, n: int = 4, grout: float = 0.035):
    """n x n square tiles, each a slightly different shade, separated by grout lines."""
    y, x = _grid(size)
    iy, ix = np.floor(y * n).astype(int), np.floor(x * n).astype(int)
    jitter = rng.uniform(0.88, 1.08, (n, n))[iy, ix]
    fy, fx = (y * n) % 1.0, (x * n) % 1.0
    line = (np.minimum(fy, 1 - fy) < grout) | (np.minimum(fx, 1 - fx) < grout)
    surface = 0.9 + 0.1 * periodic_noise(rng, size, beta=1.5)
    out = np.asarray(rgb, float) * (jitter * surface)[..., None]
    out[line] = _shade(rgb, 0.5)
    return out


def brick(rng, size, rgb, rows: int = 8, cols: int = 4, mortar: float = 0.06):
    """Running-bond bricks (every other row shifted half a brick) in light mortar."""
    y, x = _grid(size)
    row = np.floor(y * rows).astype(int)
    xs = (x * cols + 0.5 * (row % 2)) % cols
    col = np.floor(xs).astype(int)
    jitter = rng.uniform(0.8, 1.1, (rows, cols))[row, col]
    fy, fx = (y * rows) % 1.0, xs % 1.0
    line = (np.minimum(fy, 1 - fy) < mortar) | (np.minimum(fx, 1 - fx) < mortar / 2)
    rough = 0.85 + 0.15 * periodic_noise(rng, size, beta=1.0)
    out = np.asarray(rgb, float) * (jitter * rough)[..., None]
    out[line] = (0.72, 0.70, 0.66)
    return out


def fabric(rng, size, rgb, threads: int = 64):
    """A plain weave: alternating over / under threads, with slub noise."""
    y, x = _grid(size)
    weave = np.sin(2 * np.pi * threads * x) * np.sin(2 * np.pi * threads * y)
    slub = periodic_noise(rng, size, beta=1.5, stretch=(1.0, 8.0))
    return np.asarray(rgb, float) * (0.82 + 0.12 * weave + 0.12 * slub)[..., None]


def carpet(rng, size, rgb):
    """Dense short fibres: fine white noise over soft mottling."""
    mottle = periodic_noise(rng, size, beta=2.2)
    fibre = rng.random((size, size))
    return np.asarray(rgb, float) * (0.7 + 0.2 * mottle + 0.2 * fibre)[..., None]


def plaster(rng, size, rgb):
    """A painted wall: faint low-frequency unevenness and a fine trowel texture."""
    low = periodic_noise(rng, size, beta=2.8)
    fine = periodic_noise(rng, size, beta=0.8)
    return np.asarray(rgb, float) * (0.92 + 0.06 * low + 0.04 * fine)[..., None]


def concrete(rng, size, rgb):
    """Mottled grey with small dark pores."""
    low = periodic_noise(rng, size, beta=2.5)
    pores = rng.random((size, size)) < 0.01
    out = np.asarray(rgb, float) * (0.8 + 0.25 * low)[..., None]
    out[pores] *= 0.55
    return out


def terrazzo(rng, size, rgb, chips: int = 140):
    """A light matrix with scattered coloured stone chips (wrapped at the tile's edges)."""
    out = np.asarray(rgb, float) * (0.95 + 0.05 * periodic_noise(rng, size, beta=2.0))[..., None]
    y, x = np.mgrid[0:size, 0:size]
    palette = [(0.55, 0.2, 0.15), (0.25, 0.3, 0.2), (0.2, 0.2, 0.22), (0.75, 0.65, 0.45)]
    for _ in range(chips):
        cy, cx = rng.uniform(0, size, 2)
        r = rng.uniform(1.0, 0.025 * size)
        dy = np.minimum(np.abs(y - cy), size - np.abs(y - cy))
        dx = np.minimum(np.abs(x - cx), size - np.abs(x - cx))
        out[dy**2 + dx**2 < r**2] = (
            _shade(rgb, rng.uniform(0.35, 0.8))
            if rng.random() < 0.7
            else palette[int(rng.integers(len(palette)))]
        )
    return out


def brushed_metal(rng, size, rgb):
    """Fine streaks along one direction."""
    streaks = periodic_noise(rng, size, beta=1.0, stretch=(1.0, 40.0))
    return np.asarray(rgb, float) * (0.8 + 0.3 * streaks)[..., None]


def plastic(rng, size, rgb):
    """Nearly uniform, with a faint moulding texture."""
    return np.asarray(rgb, float) * (0.96 + 0.04 * periodic_noise(rng, size, beta=1.8))[..., None]


def cardboard(rng, size, rgb):
    """Brown paper fibres with the faint stripes of the corrugation beneath."""
    _, x = _grid(size)
    flutes = 0.5 + 0.5 * np.sin(2 * np.pi * 16 * x)
    fibres = periodic_noise(rng, size, beta=1.3, stretch=(1.0, 5.0))
    return np.asarray(rgb, float) * (0.82 + 0.06 * flutes + 0.16 * fibres)[..., None]


FAMILIES: dict[str, Callable] = {
    "wood": wood,
    "marble": marble,
    "granite": granite,
    "tiles": tiles,
    "brick": brick,
    "fabric": fabric,
    "carpet": carpet,
    "plaster": plaster,
    "concrete": concrete,
    "terrazzo": terrazzo,
    "brushed_metal": brushed_metal,
    "plastic": plastic,
    "cardboard": cardboard,
}


def make_texture(family: str, seed: int, rgb: Rgb, size: int = 256) -> np.ndarray:
    """An (size, size, 3) uint8 seamless tile of ``family`` around the base colour ``rgb`` (0-1),
    read-only (cached: every ID scene reuses the same few)."""
    if family not in FAMILIES:
        raise ValueError(f"unknown texture family {family!r}; choose from {sorted(FAMILIES)}")
    if size < 32 or size & (size - 1):
        raise ValueError(f"texture size must be a power of two >= 32, got {size}")
    return _texture(family, int(seed), tuple(float(c) for c in rgb), int(size))


@lru_cache(maxsize=64)
def _texture(family: str, seed: int, rgb: Rgb, size: int) -> np.ndarray:
    out = FAMILIES[family](np.random.default_rng(seed), size, rgb)
    img = (np.clip(out, 0.0, 1.0) * 255 + 0.5).astype(np.uint8)
    img.flags.writeable = False
    return img
