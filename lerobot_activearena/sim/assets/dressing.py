"""How task objects look: lathed meshes for the round ones (``look/dress.py`` draws them in place
of the primitives that collide). Each function returns the parts for one object's parameters; every
part stays inside the object's collision extents (``tests/sim/test_dressing.py``)."""

from __future__ import annotations

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..look.dress import Dress
from ..look.meshes import extrude, lathe, rotated, scaled
from .base import add_texture_material

METAL = (0.78, 0.78, 0.8, 1.0)
DARK = (0.12, 0.12, 0.13, 1.0)


def _arc(
    r: float, z0: float, height: float, n: int = 10, start_deg: float = 0.0
) -> list[tuple[float, float]]:
    """Quarter ellipse from (r, z0) up to the axis at z0 + height."""
    phi = np.radians(np.linspace(start_deg, 90.0, n))
    pts = [(r * np.cos(p), z0 + height * np.sin(p)) for p in phi]
    return [(max(float(x), 0.0), float(z)) for x, z in pts[:-1]] + [(0.0, z0 + height)]


def bell(radius: float, rgba, base_rgba) -> list[Dress]:
    """A desk bell: a bevelled base and a dome up to the plunger (z 0.051)."""
    base = [(0.0, 0.0), (radius, 0.0), (radius, 0.012), (0.95 * radius, 0.016), (0.0, 0.016)]
    dome = [(0.0, 0.016), *_arc(0.85 * radius, 0.016, 0.035, 12)]
    return [Dress(lathe(base), base_rgba), Dress(lathe(dome), rgba)]


def cup(radius: float, height: float, rgba) -> list[Dress]:
    """An open cup: rounded foot, thin rim, a hollow inside down to its floor."""
    wall = 0.1 * radius
    profile = [
        (0.0, 0.0),
        (0.9 * radius, 0.0),
        (radius, 0.006),
        (radius, height),
        (radius - wall, height),
        (radius - wall, 0.012),
        (0.0, 0.012),
    ]
    return [Dress(lathe(profile), rgba)]


def label(spec, name: str, rgba, text: str, band: tuple[float, float], size=(256, 128)) -> str:
    """A wrap-around label material for a lathed body (u: once around, v: along the profile from the
    bottom): the object's colour, a white band over ``band`` (v range) with ``text`` twice round."""
    img = Image.new("RGB", size, tuple(int(255 * c) for c in rgba[:3]))
    draw = ImageDraw.Draw(img)
    y0, y1 = (int(size[1] * (1.0 - v)) for v in band[::-1])  # drawn upright, then turned (below)
    draw.rectangle([0, y0, size[0], y1], fill=(245, 245, 240))
    font = ImageFont.load_default(size=max(8, int(0.7 * (y1 - y0))))
    for u in (0.25, 0.75):
        draw.text((u * size[0], 0.5 * (y0 + y1)), text, fill=(30, 30, 35), font=font, anchor="mm")
    # MuJoCo reads image row 0 at v = 0 (the profile's bottom): flip the upright drawing.
    return add_texture_material(spec, f"{name}_label", np.asarray(img.transpose(Image.FLIP_TOP_BOTTOM)))


def can(spec, name: str, radius: float, height: float, rgba) -> list[Dress]:
    """A drink can: a body with rolled edges and a printed label, and a metal top with its rim (to
    ``height`` + 8 mm)."""
    body = [
        (0.0, 0.0),
        (0.88 * radius, 0.0),
        (radius, 0.01),
        (radius, height - 0.008),
        (0.9 * radius, height),
        (0.0, height),
    ]
    top = [
        (0.0, height),
        (0.9 * radius, height),
        (0.85 * radius, height + 0.008),
        (0.8 * radius, height + 0.008),
        (0.78 * radius, height + 0.004),
        (0.0, height + 0.004),
    ]
    material = label(spec, name, rgba, "FIZZ", (0.45, 0.6))
    return [Dress(lathe(body), material=material), Dress(lathe(top), METAL)]


def bottle(spec, name: str, radius: float, height: float, body_height: float, rgba) -> list[Dress]:
    """A bottle: body with a printed label, rounded shoulder into the neck (0.4 of the radius), a
    white cap."""
    neck = 0.4 * radius
    shoulder = body_height - 0.25 * radius
    cap_z = height - 0.02
    body = [
        (0.0, 0.0),
        (0.9 * radius, 0.0),
        (radius, 0.008),
        (radius, shoulder),
        *[
            (
                neck + (radius - neck) * float(np.cos(p)),
                shoulder + (body_height + 0.02 - shoulder) * float(np.sin(p)),
            )
            for p in np.radians(np.linspace(20.0, 90.0, 6))
        ],
        (neck, cap_z),
        (0.0, cap_z),
    ]
    cap = [(0.0, cap_z), (1.05 * neck, cap_z), (1.05 * neck, height - 0.002), (neck, height), (0.0, height)]
    material = label(spec, name, rgba, "AQUA", (0.3, 0.45))
    return [Dress(lathe(body), material=material), Dress(lathe(cap), (0.95, 0.95, 0.95, 1.0))]


def plate(rgba) -> list[Dress]:
    """A plate: a foot, a bevelled rim, the flat well where things are set (z 0.014)."""
    profile = [
        (0.0, 0.0),
        (0.06, 0.0),
        (0.065, 0.006),
        (0.09, 0.011),
        (0.095, 0.0135),
        (0.092, 0.014),
        (0.0, 0.014),
    ]
    return [Dress(lathe(profile, segments=48), rgba)]


def pill_bottle(rgba) -> list[Dress]:
    """A pill bottle: rounded body, a ribbed white cap (z 0.07-0.088)."""
    body = [(0.0, 0.0), (0.02, 0.0), (0.022, 0.003), (0.022, 0.068), (0.019, 0.07), (0.0, 0.07)]
    cap = [(0.0, 0.07), (0.024, 0.07), (0.024, 0.086), (0.022, 0.088), (0.0, 0.088)]
    return [Dress(lathe(body), rgba), Dress(lathe(cap), (0.96, 0.96, 0.96, 1.0))]


def mouse(rgba) -> list[Dress]:
    """A computer mouse: an oval dome, flat underneath, 11 x 6.4 x 3.6 cm (its ellipsoid's box)."""
    dome = [(0.0, 0.0), (0.9, 0.0), (1.0, 0.12), *_arc(0.98, 0.2, 0.8, 12, 12.0)]
    return [Dress(scaled(lathe(dome, segments=40), 0.055, 0.032, 0.036), rgba)]


def shoe(rgba, sole_rgba=(0.95, 0.95, 0.93, 1.0)) -> list[Dress]:
    """A shoe: a rounded sole, an oval upper over the toes and the vamp, an open heel counter."""
    sole = [(0.0, 0.0), (0.97, 0.0), (1.0, 0.4), (0.97, 1.0), (0.0, 1.0)]
    upper = [(0.0, 0.0), *_arc(1.0, 0.0, 1.0, 12)]
    heel = [(0.0, 0.0), (1.0, 0.0), (1.0, 0.8), (0.92, 1.0), (0.75, 1.0), (0.75, 0.45), (0.0, 0.45)]  # open
    return [
        Dress(scaled(lathe(sole, segments=40), 0.12, 0.04, 0.016), sole_rgba),
        Dress(scaled(lathe(upper, segments=40), 0.09, 0.036, 0.05), rgba, pos=(0.01, 0.0, 0.016)),
        Dress(scaled(lathe(heel, segments=32), 0.035, 0.036, 0.064), rgba, pos=(-0.08, 0.0, 0.016)),
    ]


def seal_handle(rgba) -> list[Dress]:
    """A rubber stamp's turned handle: a collar on the base, a waist, a round knob (to z 0.103)."""
    profile = [
        (0.0, 0.02),
        (0.012, 0.02),
        (0.012, 0.028),
        (0.009, 0.04),
        (0.009, 0.06),
        (0.011, 0.068),
        *_arc(0.018, 0.085, 0.018, 8, -60.0),
    ]
    return [Dress(lathe(profile), rgba)]


def display_stand(rgba) -> list[Dress]:
    """A pedestal: a bevelled foot, a slim column, the flat top things stand on (z 0.08)."""
    profile = [
        (0.0, 0.0),
        (0.045, 0.0),
        (0.045, 0.008),
        (0.036, 0.012),
        (0.012, 0.014),
        (0.012, 0.07),
        (0.048, 0.072),
        (0.05, 0.075),
        (0.05, 0.08),
        (0.0, 0.08),
    ]
    return [Dress(lathe(profile, segments=40), rgba)]


def coaster(radius: float, rgba) -> list[Dress]:
    """A coaster: a disc with a rounded edge (its cork insert stays drawn on top)."""
    profile = [
        (0.0, 0.0),
        (0.96 * radius, 0.0),
        (radius, 0.002),
        (radius, 0.005),
        (0.97 * radius, 0.006),
        (0.0, 0.006),
    ]
    return [Dress(lathe(profile, segments=40), rgba)]


def rounded_rectangle(half_x: float, half_y: float, corner: float, n: int = 6) -> list[tuple[float, float]]:
    """A counter-clockwise outline of a rectangle (half sizes) with quarter-circle corners."""
    pts = []
    for cx, cy, start in ((1, 1, 0), (-1, 1, 90), (-1, -1, 180), (1, -1, 270)):
        ox, oy = cx * (half_x - corner), cy * (half_y - corner)
        for a in np.radians(np.linspace(start, start + 90, n)):
            pts.append((ox + corner * np.cos(a), oy + corner * np.sin(a)))
    return pts


def button(
    half: tuple[float, float],
    height: float,
    cap_at: float,
    cap_radius: float,
    cap_height: float,
    rgba,
    cap_rgba,
) -> tuple[list[Dress], list[Dress]]:
    """A push button: a slab with rounded corners and a metal bezel round the cap (on the base), and
    a cap with a domed top (on the cap's body). Returns (base parts, cap parts)."""
    slab = Dress(extrude(rounded_rectangle(*half, corner=0.008), height), rgba)
    bezel_profile = [
        (cap_radius + 0.0005, 0.0),
        (cap_radius + 0.004, 0.0),
        (cap_radius + 0.003, 0.003),
        (cap_radius + 0.0005, 0.003),
    ]
    bezel = Dress(lathe(bezel_profile, segments=40), METAL, pos=(cap_at, 0.0, height))
    dome = [
        (0.0, 0.0),
        (cap_radius, 0.0),
        *_arc(cap_radius, 0.6 * cap_height, 0.4 * cap_height, 8),
    ]
    return [slab, bezel], [Dress(lathe(dome, segments=40), cap_rgba)]


def electronic_scale(half: tuple[float, float], height: float, rgba) -> list[Dress]:
    """A kitchen scale: a dark housing with rounded corners and a brushed platform inset on top."""
    housing_h = height - 0.006
    housing = Dress(extrude(rounded_rectangle(*half, corner=0.012), housing_h), DARK)
    inset = (half[0] - 0.012, half[1] - 0.004)
    platform = Dress(
        extrude(rounded_rectangle(*inset, corner=0.01), 0.006), rgba, pos=(0.012, 0.0, housing_h)
    )
    return [housing, platform]


def switch(
    half: tuple[float, float], height: float, rocker_half: tuple[float, float, float], rgba, rocker_rgba
):
    """A rocker switch: a base with rounded corners (on the base) and a rounded rocker (on the
    rocker's hinged body, centred on it). Returns (base parts, rocker parts)."""
    base = Dress(extrude(rounded_rectangle(*half, corner=0.008), height), rgba)
    hx, hy, hz = rocker_half
    rocker = Dress(extrude(rounded_rectangle(hx, hy, corner=0.005), 2 * hz), rocker_rgba, pos=(0.0, 0.0, -hz))
    return [base], [rocker]


def hammer(handle_rgba, head_rgba) -> list[Dress]:
    """A hammer: a round handle tapering towards the head (along x, -0.1 to 0.1 m) and a head with
    bevelled faces across it (along y, centred at x 0.11)."""
    handle = [
        (0.0, 0.0),
        (0.011, 0.0),
        (0.012, 0.008),
        (0.012, 0.12),
        (0.009, 0.19),
        (0.009, 0.2),
        (0.0, 0.2),
    ]
    head = [(0.0, 0.0), (0.016, 0.0), (0.018, 0.004), (0.018, 0.096), (0.016, 0.1), (0.0, 0.1)]
    return [
        Dress(rotated(lathe(handle, segments=24), (0, 1, 0), np.pi / 2), handle_rgba, pos=(-0.1, 0.0, 0.012)),
        Dress(rotated(lathe(head, segments=24), (1, 0, 0), -np.pi / 2), head_rgba, pos=(0.11, -0.05, 0.018)),
    ]


def stapler(rgba, base_rgba) -> tuple[list[Dress], list[Dress]]:
    """A desk stapler: a base plate and a rear post with rounded corners (on the base), and a top arm
    with a rounded nose, its side profile extruded across its width (on the hinged arm's body, which
    sits on the post: the arm runs from x -0.002 to 0.134 m there). Returns (base, arm) parts."""
    plate = Dress(extrude(rounded_rectangle(0.075, 0.02, corner=0.012), 0.012), base_rgba)
    post = Dress(
        extrude(rounded_rectangle(0.012, 0.016, corner=0.004), 0.024), base_rgba, pos=(-0.062, 0.0, 0.012)
    )
    side = [
        (-0.002, -0.008),
        (0.126, -0.008),
        (0.134, -0.003),
        (0.134, 0.001),
        (0.124, 0.008),
        (-0.002, 0.008),
    ]
    arm = rotated(extrude(side, 0.034), (1, 0, 0), np.pi / 2)
    return [plate, post], [Dress(arm, rgba, pos=(0.0, 0.017, 0.0))]


def fan(rgba, dark) -> list[Dress]:
    """A desk fan (its axis along x, facing -x): a bevelled base, a motor housing with a rounded back,
    and a guard ring around three blades (the stand and the hub stay as they are)."""
    turn_to_x = ((0, 1, 0), np.pi / 2)  # lathe / extrusion axis z -> x
    base = [(0.0, 0.0), (0.045, 0.0), (0.045, 0.01), (0.04, 0.016), (0.0, 0.016)]
    housing = [(0.0, 0.0), (0.017, 0.0), (0.019, 0.004), (0.019, 0.06), (0.015, 0.068), (0.0, 0.07)]
    ring = [(0.046, 0.0), (0.052, 0.0), (0.052, 0.008), (0.046, 0.008)]
    t = np.linspace(0.0, 2 * np.pi, 16, endpoint=False)
    blade = np.stack([0.028 + 0.016 * np.cos(t), 0.009 * np.sin(t)], axis=1)  # an oval, hub to rim
    parts = [
        Dress(lathe(base, segments=40), dark),
        Dress(rotated(lathe(housing, segments=32), *turn_to_x), dark, pos=(-0.04, 0.0, 0.11)),
        Dress(rotated(lathe(ring, segments=48), *turn_to_x), rgba, pos=(-0.049, 0.0, 0.11)),
    ]
    for k in range(3):
        a = 2 * np.pi * k / 3
        rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
        outline = [tuple(p) for p in blade @ rot.T]
        parts.append(Dress(rotated(extrude(outline, 0.003), *turn_to_x), rgba, pos=(-0.047, 0.0, 0.11)))
    return parts


def _shaded(rgba, towards: float = 0.5, weight: float = 0.4):
    """``rgba`` mixed towards grey ``towards``: a rim that reads on black and white alike."""
    return (*((1 - weight) * c + weight * towards for c in rgba[:3]), rgba[3])


def pad(half_x: float, half_y: float, height: float, rgba, corner: float = 0.01) -> list[Dress]:
    """A mat or pad: a rounded slab with a stitched-looking rim (a shade towards grey) 4 mm wide."""
    rim = 0.004
    return [
        Dress(extrude(rounded_rectangle(half_x, half_y, corner), 0.85 * height), _shaded(rgba)),
        Dress(extrude(rounded_rectangle(half_x - rim, half_y - rim, corner - rim / 2), height), rgba),
    ]


def _ring_halves(
    half_x: float, half_y: float, wall: float, corner: float, n: int = 6
) -> list[list[tuple[float, float]]]:
    """The wall of a rounded box seen from above, as two simple counter-clockwise U-shapes (the
    halves y <= 0 and y >= 0) that ``extrude`` can triangulate."""
    outer = rounded_rectangle(half_x, half_y, corner, n)
    inner = rounded_rectangle(half_x - wall, half_y - wall, max(corner - wall, 0.002), n)
    halves = []
    for sign in (-1, 1):
        # rounded_rectangle starts at +x and runs counter-clockwise: the lower half is its second
        # half, the upper its first; each goes from one side (x = +-half_x) to the other
        o = [p for p in outer if sign * p[1] >= 0]
        i = [p for p in inner if sign * p[1] >= 0]
        if sign < 0:  # from (-x, 0) under to (+x, 0)
            o = [(-half_x, 0.0), *o, (half_x, 0.0)]
            i = [(-(half_x - wall), 0.0), *i, (half_x - wall, 0.0)]
        else:  # from (+x, 0) over to (-x, 0)
            o = [(half_x, 0.0), *o, (-half_x, 0.0)]
            i = [(half_x - wall, 0.0), *i, (-(half_x - wall), 0.0)]
        halves.append(o + i[::-1])
    return halves


def open_box(
    half_x: float, half_y: float, wall: float, height: float, rgba, corner: float = 0.018, material=None
):
    """A tray or basket: a rounded floor ``wall`` thick and rounded walls up to ``height``."""
    parts = [Dress(extrude(rounded_rectangle(half_x, half_y, corner), wall), rgba, material=material)]
    for half in _ring_halves(half_x, half_y, wall, corner):
        parts.append(Dress(extrude(half, height), rgba, material=material))
    return parts


def food_container(half_x: float, half_y: float, body_height: float, lid_height: float, rgba, lid_rgba):
    """A food container: a rounded tub and a rounded lid on top of it."""
    outline = rounded_rectangle(half_x, half_y, 0.4 * min(half_x, half_y))
    return [
        Dress(extrude(outline, body_height), rgba),
        Dress(extrude(outline, lid_height), lid_rgba, pos=(0, 0, body_height)),
    ]


def basket_weave(rgb, size: int = 64, cells: int = 4) -> np.ndarray:
    """A seamless (size, size, 3) uint8 wicker tile: cells of three strands, horizontal and vertical
    in turn, with dark gaps between the strands."""
    y, x = np.mgrid[0:size, 0:size]
    cell = size // cells
    horizontal = ((x // cell + y // cell) % 2) == 0
    along = np.where(horizontal, y, x) % cell  # position across the strands of the cell
    strand = cell // 3
    t = (along % strand) / strand  # 0..1 across one strand
    shade = 0.75 + 0.35 * np.sin(np.pi * t)  # rounded strands
    shade = np.where((along % strand) == 0, 0.45, shade)  # the gaps
    img = np.clip(np.asarray(rgb, float)[None, None, :3] * shade[..., None], 0.0, 1.0)
    return (img * 255 + 0.5).astype(np.uint8)
