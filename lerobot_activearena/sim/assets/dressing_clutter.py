"""How distractors look: lathed profiles drawn in place of the round ones' stacked cylinders and
spheres, and extruded slabs with code-drawn textures in place of the flat ones' boxes (a book's
boards and pages, a sponge, a tissue box). ``distractors.py`` names which parts each replaces; every
function takes ``(spec, name, rgba)`` (textures need the object's name) and returns its meshes.
Profiles run from the object's foot (z = 0) up, in metres; every mesh stays inside the object's
collision extents (``tests/sim/test_dressing.py``). Kept small (20 segments, 64-pixel textures) so
that a dense OOD table of them costs little to draw."""

from __future__ import annotations

import numpy as np

from ..look.dress import Dress
from ..look.meshes import extrude, lathe
from ..look.textures import make_texture
from .base import add_texture_material
from .dressing import _arc, rounded_rectangle

SEGMENTS = 20
STEEL = (0.72, 0.73, 0.76, 1.0)
DARK = (0.1, 0.1, 0.11, 1.0)
SOIL = (0.25, 0.17, 0.1, 1.0)
TERRACOTTA = (0.75, 0.38, 0.2, 1.0)
GOLD = (0.9, 0.75, 0.2, 1.0)
PAPER = (0.95, 0.93, 0.86)


def _lathe(profile) -> object:
    return lathe(profile, segments=SEGMENTS)


def _ellipse(rx: float, rz: float, zc: float, degrees) -> list[tuple[float, float]]:
    """Profile points on an ellipse centred on the axis at height ``zc``, at ``degrees`` above the
    horizontal (a pawn's head, a bulb's glass, a teapot's belly)."""
    return [(rx * np.cos(a), zc + rz * np.sin(a)) for a in np.radians(degrees)]


def candle(spec, name, rgba) -> list[Dress]:
    """A pillar candle with a soft, sunken top on a brass dish."""
    dish = [(0.0, 0.0), (0.04, 0.0), (0.045, 0.006), (0.043, 0.008), (0.03, 0.007), (0.0, 0.007)]
    wax = [(0.0, 0.007), (0.024, 0.007), (0.024, 0.084), (0.021, 0.088), (0.012, 0.085), (0.0, 0.084)]
    return [Dress(_lathe(dish), (0.8, 0.65, 0.25, 1.0)), Dress(_lathe(wax), rgba)]


def chess_pawn(spec, name, rgba) -> list[Dress]:
    """A turned pawn: foot, waist, collar and head."""
    profile = [
        (0.0, 0.0),
        (0.022, 0.0),
        (0.022, 0.005),
        (0.017, 0.009),
        (0.012, 0.016),
        (0.009, 0.04),
        (0.015, 0.054),
        (0.016, 0.058),
        (0.01, 0.06),
        *_ellipse(0.016, 0.016, 0.07, [-40.0, -15.0, 10.0, 35.0, 60.0, 80.0]),
        (0.0, 0.086),
    ]
    return [Dress(_lathe(profile), rgba)]


def pepper_grinder(spec, name, rgba) -> list[Dress]:
    """A waisted wooden mill with a steel knob."""
    body = [
        (0.0, 0.0),
        (0.022, 0.0),
        (0.024, 0.004),
        (0.024, 0.02),
        (0.018, 0.027),
        (0.015, 0.045),
        (0.019, 0.075),
        (0.016, 0.104),
        (0.022, 0.112),
        (0.024, 0.122),
        (0.021, 0.133),
        (0.0, 0.136),
    ]
    knob = [(0.0, 0.135), (0.007, 0.135), *_arc(0.008, 0.14, 0.008, 4)]
    return [Dress(_lathe(body), rgba), Dress(_lathe(knob), STEEL)]


def kettle(spec, name, rgba) -> list[Dress]:
    """A kettle's body tapering to its lid, on a dark base, with a knob."""
    base = [(0.0, 0.0), (0.055, 0.0), (0.058, 0.004), (0.058, 0.012), (0.0, 0.012)]
    body = [(0.0, 0.011), (0.055, 0.011), (0.055, 0.085), (0.05, 0.108), (0.038, 0.122), (0.0, 0.124)]
    knob = [(0.0, 0.123), (0.006, 0.123), (0.008, 0.128), *_arc(0.012, 0.129, 0.005, 4)]
    return [Dress(_lathe(base), DARK), Dress(_lathe(body), rgba), Dress(_lathe(knob), DARK)]


def trophy_cup(spec, name, rgba) -> list[Dress]:
    """A trophy's stem and open gold cup (the handles and plinth stay as they are)."""
    profile = [
        (0.0, 0.024),
        (0.013, 0.024),
        (0.008, 0.03),
        (0.006, 0.06),
        (0.01, 0.074),
        (0.02, 0.08),
        (0.027, 0.095),
        (0.03, 0.124),
        (0.027, 0.124),
        (0.024, 0.1),
        (0.0, 0.094),
    ]
    return [Dress(_lathe(profile), GOLD)]


def _pot(r_foot: float, r_rim: float, height: float, rim: float) -> list[tuple[float, float]]:
    """A flower pot's outside and rim, closed at the soil line."""
    return [
        (0.0, 0.0),
        (r_foot, 0.0),
        (r_foot + 0.002, 0.002),
        (r_rim - 0.004, height - rim),
        (r_rim, height - rim + 0.002),
        (r_rim, height),
        (r_rim - 0.006, height),
        (0.0, height - 0.008),
    ]


def flower_pot(spec, name, rgba) -> list[Dress]:
    return [Dress(_lathe(_pot(0.034, 0.045, 0.08, 0.016)), TERRACOTTA)]


def cactus_pot(spec, name, rgba) -> list[Dress]:
    return [Dress(_lathe(_pot(0.026, 0.035, 0.05, 0.012)), (0.85, 0.8, 0.7, 1.0))]


def lightbulb(spec, name, rgba) -> list[Dress]:
    """A screw base with threads and a pear-shaped glass bulb."""
    threads = [(0.0, 0.0), (0.006, 0.0), (0.011, 0.002)]
    for z in np.arange(0.005, 0.025, 0.004):
        threads += [(0.013, float(z)), (0.0115, float(z) + 0.002)]
    threads += [(0.013, 0.026), (0.0, 0.026)]
    glass = [
        (0.0, 0.025),
        (0.013, 0.025),
        (0.016, 0.033),
        *_ellipse(0.03, 0.03, 0.05, [-40.0, -15.0, 10.0, 35.0, 60.0, 80.0]),
        (0.0, 0.08),
    ]
    return [Dress(_lathe(threads), STEEL), Dress(_lathe(glass), (0.98, 0.98, 0.85, 0.9))]


def pear(spec, name, rgba) -> list[Dress]:
    """A pear's round bottom narrowing to its neck."""
    profile = [
        (0.0, 0.0),
        (0.017, 0.003),
        (0.029, 0.012),
        (0.035, 0.03),
        (0.033, 0.046),
        (0.026, 0.058),
        (0.021, 0.07),
        (0.021, 0.08),
        (0.017, 0.091),
        (0.009, 0.097),
        (0.0, 0.099),
    ]
    return [Dress(_lathe(profile), rgba)]


def teapot(spec, name, rgba) -> list[Dress]:
    """A teapot's belly, shoulder, lid and knob in one turned piece (spout and handle stay)."""
    belly = _ellipse(0.06, 0.05, 0.052, [-60.0, -35.0, -10.0, 15.0, 40.0])
    profile = [
        (0.0, 0.0),
        (0.038, 0.0),
        (0.04, 0.004),
        *belly,
        (0.025, 0.1),
        (0.02, 0.1),
        (0.02, 0.104),
        (0.017, 0.109),
        (0.005, 0.112),
        (0.007, 0.118),
        (0.004, 0.124),
        (0.0, 0.125),
    ]
    return [Dress(_lathe(profile), rgba)]


def tape_roll(spec, name, rgba) -> list[Dress]:
    """A roll of tape around a cardboard core, hollow through the middle."""
    tape = [(0.028, 0.0), (0.042, 0.0), (0.042, 0.026), (0.028, 0.026), (0.028, 0.0)]  # a closed loop
    core = [(0.0235, 0.0), (0.0278, 0.0), (0.0278, 0.026), (0.0235, 0.026), (0.0235, 0.0)]
    return [Dress(_lathe(tape), rgba), Dress(_lathe(core), (0.55, 0.45, 0.35, 1.0))]


# ---- flat ones: extruded slabs with textures ----------------------------------------------------
def _material(spec, name: str, img: np.ndarray, tile_m: float) -> str:
    """A material repeating ``img`` once every ``tile_m`` metres (extruded meshes' texture
    coordinates are in metres)."""
    return add_texture_material(spec, name, img, texrepeat=(1.0 / tile_m, 1.0 / tile_m))


def page_edges(size: int = 64, pages: int = 32) -> np.ndarray:
    """A seamless tile of paper edges: thin grey lines between pages along the tile's rows."""
    y = np.arange(size)[:, None] * np.ones((1, size))
    shade = np.where((y * pages // size) % 2 == 0, 1.0, 0.86)
    img = np.asarray(PAPER)[None, None, :] * shade[..., None]
    return (np.clip(img, 0, 1) * 255 + 0.5).astype(np.uint8)


def diagonal_stripes(rgb, size: int = 64, stripes: int = 4) -> np.ndarray:
    """A seamless tile of ``rgb`` and white diagonal stripes (a printed carton)."""
    y, x = np.mgrid[0:size, 0:size]
    band = ((x + y) * stripes // size) % 2 == 0
    img = np.where(band[..., None], np.asarray(rgb[:3], float), np.asarray((0.97, 0.97, 0.95)))
    return (img * 255 + 0.5).astype(np.uint8)


def book(spec, name, rgba) -> list[Dress]:
    """Two cloth-covered boards joined by a spine, with the page block between them."""
    cloth = _material(spec, f"{name}_cloth", make_texture("fabric", 7, tuple(rgba[:3]), 64), 0.03)
    pages = _material(spec, f"{name}_pages", page_edges(), 0.016)
    board = extrude(rounded_rectangle(0.1, 0.07, 0.004), 0.003)
    return [
        Dress(board, material=cloth),
        Dress(board, material=cloth, pos=(0.0, 0.0, 0.027)),
        Dress(
            extrude(rounded_rectangle(0.003, 0.07, 0.0015), 0.024), material=cloth, pos=(-0.097, 0.0, 0.003)
        ),
        Dress(
            extrude(rounded_rectangle(0.0965, 0.067, 0.001), 0.024), material=pages, pos=(0.0025, 0.0, 0.003)
        ),
    ]


def sponge(spec, name, rgba) -> list[Dress]:
    """A porous yellow block under a green scouring pad."""
    foam = _material(spec, f"{name}_foam", make_texture("concrete", 3, (0.98, 0.86, 0.25), 64), 0.02)
    pad = _material(spec, f"{name}_pad", make_texture("carpet", 5, (0.15, 0.6, 0.25), 64), 0.02)
    return [
        Dress(extrude(rounded_rectangle(0.05, 0.032, 0.006), 0.024), material=foam),
        Dress(extrude(rounded_rectangle(0.05, 0.032, 0.004), 0.01), material=pad, pos=(0.0, 0.0, 0.024)),
    ]


def tissue_box(spec, name, rgba) -> list[Dress]:
    """A carton printed with diagonal stripes of its colour (the tissue stays as it is)."""
    print_ = _material(spec, f"{name}_print", diagonal_stripes(rgba), 0.04)
    return [Dress(extrude(rounded_rectangle(0.065, 0.05, 0.004), 0.09), material=print_)]
