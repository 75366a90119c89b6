"""Task-named household objects (paper task inventory): hammer, stapler, switch, pill bottle,
Rubik's cube, wooden block, coffee box, plastic box, container, plate, fan, mouse, bread basket,
electronic scale, display stand, shoe, seal, mats in named colours, and a can with a rear label
(production date or colour)."""

from __future__ import annotations

import datetime as dt

import mujoco
import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..look.dress import dress
from ..look.textures import make_texture
from . import dressing
from .base import ObjectInfo, add_geom, add_texture_material, free_body, static_body
from .functional import Container, Functional, InfoFace, Press, Support, ToolHead
from .registry import register_asset
from .shapes import arc_label, compound, quat_axis_angle, text_texture

MAT_COLORS = {
    "red": (0.85, 0.15, 0.12),
    "green": (0.15, 0.65, 0.25),
    "blue": (0.15, 0.3, 0.85),
    "yellow": (0.95, 0.85, 0.15),
    "black": (0.08, 0.08, 0.09),
    "silver": (0.75, 0.76, 0.78),
    "cyan": (0.1, 0.8, 0.85),
    "beige": (0.9, 0.82, 0.65),
    "pink": (0.95, 0.55, 0.7),
    "orange": (0.95, 0.5, 0.1),
    "purple": (0.55, 0.25, 0.7),
    "white": (0.96, 0.96, 0.96),
    "magenta": (0.85, 0.15, 0.75),
    "gray": (0.45, 0.45, 0.47),
}
RELEASE_MAT_COLORS = ("red", "green", "blue", "yellow", "cyan", "magenta", "black", "gray")  # stapler, mouse
DATE_RANGE = (dt.date(2023, 1, 1), dt.date(2026, 12, 31))  # paper: production dates
SHELF_LIFE_DAYS = 365
YAXIS_90 = quat_axis_angle([0, 1, 0], np.pi / 2)
XAXIS_90 = quat_axis_angle([1, 0, 0], np.pi / 2)


def _rgba(rgb, a=1.0):
    return (*rgb, a)


def _dress_parts(spec, name: str, replaced: range | tuple[int, ...], parts) -> None:
    """Dress a ``compound`` object: its parts ``replaced`` (indices) drawn as ``parts`` instead."""
    replaces = [spec.geom(f"{name}_body" if k == 0 else f"{name}_part{k}") for k in replaced]
    dress(spec, spec.body(name), name, replaces, parts)


def _color(rng, lo=0.15, hi=0.9):
    return tuple(float(x) for x in rng.uniform(lo, hi, 3))


@register_asset(
    "hammer", footprint=0.11, role="task", randomize=lambda rng: {"handle": _color(rng, 0.3, 0.9)}
)
def add_hammer(spec, name, pos, yaw=0.0, handle=(0.6, 0.4, 0.2)):
    return compound(
        spec,
        name,
        "hammer",
        pos,
        yaw,
        [
            ("box", (0.1, 0.012, 0.012), (0.0, 0, 0.012), _rgba(handle)),
            ("box", (0.018, 0.05, 0.018), (0.11, 0, 0.018), (0.3, 0.3, 0.33, 1)),
        ],
        0.3,
        # Held across the handle near the head (the centre of mass: no lever to pitch it in the
        # pads), the TCP above the handle so the open pads stay off the table.
        functional=Functional(
            grasp=((0.055, 0.0, 0.033),),
            grasp_axis=(0.0, 1.0, 0.0),
            tool_head=ToolHead((0.11, 0.0, 0.018), (0.018, 0.05, 0.018)),
        ),
    )


def _hinge(
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


STAPLER_OPEN = 0.14  # rad the top arm rests above closed
STAPLER_PRESSED = 0.1  # rad of travel that counts as a press (of 0.14)


@register_asset("stapler", footprint=0.09, role="task", randomize=lambda rng: {"rgba": _rgba(_color(rng))})
def add_stapler(spec, name, pos, yaw=0.0, rgba=(0.1, 0.1, 0.12, 1)):
    """Desk stapler: base plate, rear post and a spring-loaded top arm hinged at the rear
    (``functional.press``'s joint: 0 = open, ``STAPLER_OPEN`` = pressed shut; press point at the front end
    of the arm, in the arm body's frame)."""
    b = free_body(spec, name, pos, yaw)
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.075, 0.02, 0.006),
        (0, 0, 0.006),
        (0.15, 0.15, 0.16, 1),
        0.2,
        f"{name}_body",
    )
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.012, 0.016, 0.012),
        (-0.062, 0, 0.024),
        (0.15, 0.15, 0.16, 1),
        0.03,
        f"{name}_post",
    )
    arm = b.add_body()
    arm.name = f"{name}_arm"
    arm.pos = (-0.062, 0, 0.036)
    arm.quat = quat_axis_angle([0, 1, 0], -STAPLER_OPEN)  # front end raised
    arm.gravcomp = 1.0
    _hinge(arm, f"{name}_joint", 0.0, STAPLER_OPEN, damping=0.05, stiffness=0.6, springref=-0.15)
    add_geom(
        arm, mujoco.mjtGeom.mjGEOM_BOX, (0.068, 0.017, 0.008), (0.066, 0, 0.0), rgba, 0.05, f"{name}_arm_geom"
    )
    return ObjectInfo(
        name,
        "stapler",
        name,
        (0.075, 0.02, 0.03),
        (0, 0, 0.03),
        0.28,
        functional=Functional(
            grasp=((0.0, 0.0, 0.03),),
            grasp_axis=(0.0, 1.0, 0.0),  # across its width: fingers along the long axis would land on the arm
            press=Press(
                (0.115, 0.0, 0.008), f"{name}_joint", STAPLER_PRESSED, direction="above", body=f"{name}_arm"
            ),
        ),
    )


SWITCH_TILT = 0.25  # rad the rocker rests tilted to each side of flat
SWITCH_ON = 2 * SWITCH_TILT  # joint value when the rocker is fully over to "on"
SWITCH_ON_AT = SWITCH_ON - 0.05  # rad: counts as switched on within 0.05 rad of the on-limit


@register_asset("switch", footprint=0.055, role="task")
def add_switch(spec, name, pos, yaw=0.0, rgba=(0.92, 0.92, 0.9, 1)):
    """Rocker switch on a small heavy base: the red rocker rests tilted with its +x end (white
    mark) up; pressing that end down rocks it over to on (``functional.press``'s joint: 0 = off,
    ``SWITCH_ON`` = on; it stays where it is put)."""
    b = free_body(spec, name, pos, yaw)
    add_geom(b, mujoco.mjtGeom.mjGEOM_BOX, (0.045, 0.03, 0.012), (0, 0, 0.012), rgba, 0.45, f"{name}_body")
    rocker = b.add_body()
    rocker.name = f"{name}_rocker"
    rocker.pos = (0, 0, 0.029)
    rocker.quat = quat_axis_angle([0, 1, 0], -SWITCH_TILT)  # +x end up: off
    rocker.gravcomp = 1.0
    _hinge(rocker, f"{name}_joint", 0.0, SWITCH_ON, damping=0.02, frictionloss=0.01)
    add_geom(
        rocker,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.038, 0.02, 0.005),
        (0, 0, 0),
        (0.8, 0.1, 0.1, 1),
        0.015,
        f"{name}_rocker_geom",
    )
    add_geom(
        rocker,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.008, 0.012, 0.0005),
        (0.026, 0, 0.005),
        (1, 1, 1, 1),
        name=f"{name}_mark",
        collide=False,
    )
    return ObjectInfo(
        name,
        "switch",
        name,
        (0.045, 0.03, 0.022),
        (0, 0, 0.022),
        0.465,
        functional=Functional(
            press=Press(
                (0.026, 0.0, 0.005), f"{name}_joint", SWITCH_ON_AT, direction="above", body=f"{name}_rocker"
            )
        ),
    )


@register_asset(
    "pill_bottle", footprint=0.03, role="task", randomize=lambda rng: {"rgba": _rgba(_color(rng, 0.5, 0.95))}
)
def add_pill_bottle(spec, name, pos, yaw=0.0, rgba=(0.95, 0.6, 0.15, 1)):
    info = compound(
        spec,
        name,
        "pill_bottle",
        pos,
        yaw,
        [
            ("cyl", (0.022, 0.035, 0), (0, 0, 0.035), _rgba(rgba[:3], 1.0)),
            ("cyl", (0.024, 0.009, 0), (0, 0, 0.079), (0.95, 0.95, 0.95, 1)),
            ("cyl", (0.0225, 0.012, 0), (0, 0, 0.035), (0.97, 0.97, 0.97, 1), {"visual": True}),
        ],
        0.08,
    )
    _dress_parts(spec, name, range(2), dressing.pill_bottle(_rgba(rgba[:3], 1.0)))
    return info


def _facelets(size=96) -> np.ndarray:
    colors = [(200, 20, 20), (20, 150, 40), (30, 60, 200), (240, 220, 30), (245, 245, 245), (240, 120, 20)]
    rng = np.random.default_rng(7)
    img = Image.new("RGB", (size, size), (15, 15, 15))
    d = ImageDraw.Draw(img)
    c = size // 3
    for i in range(3):
        for j in range(3):
            d.rectangle(
                [i * c + 3, j * c + 3, (i + 1) * c - 3, (j + 1) * c - 3], fill=colors[int(rng.integers(0, 6))]
            )
    return np.asarray(img)


@register_asset("rubiks_cube", footprint=0.04, role="task")
def add_rubiks_cube(spec, name, pos, yaw=0.0, half=0.028):
    mat = add_texture_material(spec, f"{name}_facelets", _facelets())
    return compound(
        spec,
        name,
        "rubiks_cube",
        pos,
        yaw,
        [("box", (half,) * 3, (0, 0, half), (1, 1, 1, 1), {"material": mat})],
        0.1,
    )


@register_asset("wooden_block", footprint=0.05, role="task")
def add_wooden_block(spec, name, pos, yaw=0.0, half=(0.045, 0.03, 0.025)):
    mat = add_texture_material(spec, f"{name}_wood", make_texture("wood", 11, (0.72, 0.52, 0.3), 64))
    return compound(
        spec,
        name,
        "wooden_block",
        pos,
        yaw,
        [("box", half, (0, 0, half[2]), (1, 1, 1, 1), {"material": mat})],
        0.12,
    )


@register_asset("coffee_box", footprint=0.07, role="task")
def add_coffee_box(spec, name, pos, yaw=0.0):
    mat = text_texture(spec, f"{name}_label", "COFFEE", bg=(110, 60, 30), fg=(250, 235, 200))
    return compound(
        spec,
        name,
        "coffee_box",
        pos,
        yaw,
        [("box", (0.05, 0.035, 0.06), (0, 0, 0.06), (1, 1, 1, 1), {"material": mat})],
        0.25,
        # Held 3 cm below its 12 cm top (the palm clears it) across its 7 cm side (10 cm is too wide).
        functional=Functional(grasp=((0.0, 0.0, 0.09),), grasp_axis=(0.0, 1.0, 0.0)),
    )


def _open_box(rgba, inner, wall, height):
    hx, hy = inner[0] / 2 + wall, inner[1] / 2 + wall
    return [
        ("box", (hx, hy, wall / 2), (0, 0, wall / 2), rgba),
        ("box", (wall / 2, hy, height / 2), (hx - wall / 2, 0, height / 2), rgba),
        ("box", (wall / 2, hy, height / 2), (-hx + wall / 2, 0, height / 2), rgba),
        ("box", (hx, wall / 2, height / 2), (0, hy - wall / 2, height / 2), rgba),
        ("box", (hx, wall / 2, height / 2), (0, -hy + wall / 2, height / 2), rgba),
    ]


@register_asset(
    "plastic_box",
    footprint=0.11,
    role="task",
    randomize=lambda rng: {"rgba": _rgba(_color(rng, 0.3, 0.9), 1.0)},
)
def add_plastic_box(spec, name, pos, yaw=0.0, rgba=(0.3, 0.55, 0.85, 1)):
    return compound(
        spec,
        name,
        "plastic_box",
        pos,
        yaw,
        _open_box(rgba, (0.16, 0.12), 0.006, 0.07),
        0.2,
        functional=Functional(container=Container(0.006, (0.08, 0.06), 0.07)),
    )


@register_asset("bread_basket", footprint=0.11, role="task")
def add_bread_basket(spec, name, pos, yaw=0.0, rgba=(0.62, 0.42, 0.2, 1)):
    return compound(
        spec,
        name,
        "bread_basket",
        pos,
        yaw,
        _open_box(rgba, (0.17, 0.12), 0.008, 0.05),
        0.2,
        functional=Functional(container=Container(0.008, (0.085, 0.06), 0.05)),
    )


@register_asset(
    "container", footprint=0.06, role="task", randomize=lambda rng: {"lid": _rgba(_color(rng, 0.2, 0.9))}
)
def add_container(spec, name, pos, yaw=0.0, lid=(0.2, 0.6, 0.3, 1)):
    return compound(
        spec,
        name,
        "container",
        pos,
        yaw,
        [
            ("box", (0.045, 0.035, 0.025), (0, 0, 0.025), (0.92, 0.92, 0.9, 0.95)),
            ("box", (0.045, 0.035, 0.005), (0, 0, 0.055), lid),  # flush: an overhang caught the pads
        ],
        0.12,
    )


@register_asset(
    "plate", footprint=0.1, role="task", randomize=lambda rng: {"rgba": _rgba(_color(rng, 0.7, 0.98))}
)
def add_plate(spec, name, pos, yaw=0.0, rgba=(0.96, 0.96, 0.94, 1)):
    info = compound(
        spec,
        name,
        "plate",
        pos,
        yaw,
        [
            ("cyl", (0.065, 0.004, 0), (0, 0, 0.004), rgba),
            ("cyl", (0.095, 0.003, 0), (0, 0, 0.011), rgba),
            ("cyl", (0.07, 0.0005, 0), (0, 0, 0.0145), (0.85, 0.85, 0.83, 1), {"visual": True}),
        ],
        0.3,
        functional=Functional(support=Support(0.014, (0.08, 0.08), "disc")),
    )
    _dress_parts(spec, name, range(3), dressing.plate(rgba))
    return info


@register_asset(
    "fan", footprint=0.08, role="task", randomize=lambda rng: {"rgba": _rgba(_color(rng, 0.2, 0.95))}
)
def add_fan(spec, name, pos, yaw=0.0, rgba=(0.2, 0.5, 0.85, 1)):
    """Desk fan: base, stand, a motor housing over the base behind a round guard that faces the
    body's -x side (the front), hub. Grasped across the housing above the base, near the centre of
    mass (the guard stays 2.8 cm clear of the fingers)."""
    dark = (0.2, 0.2, 0.22, 1)
    return compound(
        spec,
        name,
        "fan",
        pos,
        yaw,
        [
            ("cyl", (0.045, 0.008, 0), (0, 0, 0.008), dark),
            ("cyl", (0.007, 0.04, 0), (0, 0, 0.05), (0.3, 0.3, 0.32, 1)),
            ("cyl", (0.019, 0.035, 0), (-0.005, 0, 0.11), dark, {"quat": YAXIS_90}),
            ("cyl", (0.052, 0.004, 0), (-0.045, 0, 0.11), rgba, {"quat": YAXIS_90}),
            (
                "cyl",
                (0.016, 0.002, 0),
                (-0.051, 0, 0.11),
                (0.15, 0.15, 0.15, 1),
                {"quat": YAXIS_90, "visual": True},
            ),
        ],
        0.35,
        functional=Functional(grasp=((0.0, 0.0, 0.11),), grasp_axis=(0.0, 1.0, 0.0), front=(-1.0, 0.0, 0.0)),
    )


@register_asset(
    "mouse", footprint=0.045, role="task", randomize=lambda rng: {"rgba": _rgba(_color(rng, 0.05, 0.9))}
)
def add_mouse(spec, name, pos, yaw=0.0, rgba=(0.12, 0.12, 0.14, 1)):
    info = compound(
        spec,
        name,
        "mouse",
        pos,
        yaw,
        [
            ("ell", (0.055, 0.032, 0.018), (0, 0, 0.018), rgba),
            (
                "cyl",
                (0.006, 0.003, 0),
                (0.025, 0, 0.034),
                (0.6, 0.6, 0.62, 1),
                {"quat": XAXIS_90, "visual": True},
            ),
        ],
        0.09,
        functional=Functional(grasp_axis=(0.0, 1.0, 0.0)),  # across its width
    )
    _dress_parts(spec, name, range(1), dressing.mouse(rgba))
    return info


@register_asset("electronic_scale", footprint=0.08, role="task")
def add_electronic_scale(spec, name, pos, yaw=0.0):
    mat = text_texture(spec, f"{name}_display", "0.00 g", bg=(40, 70, 50), fg=(120, 255, 140), size=(96, 48))
    return compound(
        spec,
        name,
        "electronic_scale",
        pos,
        yaw,
        [
            ("box", (0.075, 0.065, 0.012), (0, 0, 0.012), (0.82, 0.83, 0.85, 1)),
            (
                "box",
                (0.012, 0.03, 0.0008),
                (-0.058, 0, 0.0245),
                (1, 1, 1, 1),
                {"material": mat, "visual": True, "quat": quat_axis_angle([0, 0, 1], -np.pi / 2)},
            ),
        ],
        0.5,
        functional=Functional(support=Support(0.024, (0.075, 0.065))),
    )


@register_asset("display_stand", footprint=0.05, role="task")
def add_display_stand(spec, name, pos, yaw=0.0, rgba=(0.9, 0.9, 0.92, 1)):
    info = compound(
        spec,
        name,
        "display_stand",
        pos,
        yaw,
        [
            ("cyl", (0.045, 0.006, 0), (0, 0, 0.006), rgba),
            ("cyl", (0.012, 0.03, 0), (0, 0, 0.042), rgba),
            ("cyl", (0.05, 0.004, 0), (0, 0, 0.076), rgba),
        ],
        0.3,
        functional=Functional(support=Support(0.08, (0.05, 0.05), "disc")),
    )
    _dress_parts(spec, name, range(3), dressing.display_stand(rgba))
    return info


@register_asset(
    "shoe", footprint=0.08, role="task", randomize=lambda rng: {"rgba": _rgba(_color(rng, 0.1, 0.9))}
)
def add_shoe(spec, name, pos, yaw=0.0, rgba=(0.75, 0.2, 0.2, 1)):
    info = compound(
        spec,
        name,
        "shoe",
        pos,
        yaw,
        [
            ("box", (0.12, 0.04, 0.008), (0, 0, 0.008), (0.95, 0.95, 0.93, 1)),
            ("ell", (0.09, 0.036, 0.03), (0.01, 0, 0.036), rgba),
            ("box", (0.035, 0.036, 0.04), (-0.08, 0, 0.04), rgba),
        ],
        0.3,
        functional=Functional(grasp_axis=(0.0, 1.0, 0.0)),  # across its width
    )
    _dress_parts(spec, name, range(3), dressing.shoe(rgba))
    return info


@register_asset(
    "seal", footprint=0.04, role="task", randomize=lambda rng: {"rgba": _rgba(_color(rng, 0.2, 0.9))}
)
def add_seal(spec, name, pos, yaw=0.0, rgba=(0.55, 0.25, 0.15, 1)):
    info = compound(
        spec,
        name,
        "seal",
        pos,
        yaw,
        [
            ("box", (0.025, 0.025, 0.01), (0, 0, 0.01), (0.7, 0.15, 0.12, 1)),
            ("cyl", (0.012, 0.03, 0), (0, 0, 0.05), rgba),
            ("sph", (0.018, 0, 0), (0, 0, 0.085), rgba),
        ],
        0.12,
        functional=Functional(grasp=((0.0, 0.0, 0.06),)),
    )
    _dress_parts(spec, name, (1, 2), dressing.seal_handle(rgba))
    return info


@register_asset(
    "mat",
    footprint=0.085,
    role="task",
    static=True,
    randomize=lambda rng: {"color_name": str(rng.choice(sorted(MAT_COLORS)))},
)
def add_mat(spec, name, pos, yaw=0.0, color_name: str = "black", half=(0.075, 0.06), text: str = ""):
    """Thin static mat in a named colour; ``text`` (e.g. 'EXPIRED') is printed across it in white,
    reading upright for a viewer on the body's -x side (the sampler yaws +x outward)."""
    if color_name not in MAT_COLORS:
        raise ValueError(f"unknown mat colour {color_name!r}; choose from {sorted(MAT_COLORS)}")
    b = static_body(spec, name, pos, yaw)
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_BOX,
        (*half, 0.002),
        (0, 0, 0.002),
        _rgba(MAT_COLORS[color_name]),
        None,
        f"{name}_body",
    )
    if text:
        bg = tuple(int(255 * c) for c in MAT_COLORS[color_name])
        mat = text_texture(spec, f"{name}_text", text, bg=bg, fg=(250, 250, 250), size=(256, 96), fill=0.8)
        # Texture u runs along the box's x: turned -90 deg about z, the word runs along the mat's -y.
        add_geom(
            b,
            mujoco.mjtGeom.mjGEOM_BOX,
            (0.95 * half[1], 0.36 * half[1], 0.0005),
            (0, 0, 0.0045),
            (1, 1, 1, 1),
            name=f"{name}_text",
            quat=quat_axis_angle([0, 0, 1], -np.pi / 2),
            material=mat,
            collide=False,
        )
    return ObjectInfo(
        name,
        "mat",
        name,
        (*half, 0.002),
        (0, 0, 0.002),
        0.0,
        {"color_name": color_name, "text": text},
        Functional(support=Support(0.004, tuple(half))),
    )


def random_date(rng: np.random.Generator) -> dt.date:
    span = (DATE_RANGE[1] - DATE_RANGE[0]).days
    return DATE_RANGE[0] + dt.timedelta(days=int(rng.integers(0, span + 1)))


def date_label_image(date: str, size: tuple[int, int] = (128, 176)) -> np.ndarray:
    """White label with the production date in two large lines, year over month-day (readable at
    the inspection view: ~30 px wide in the 512x384 head image)."""
    year, rest = date[:4], date[5:]
    w, h = size
    img = Image.new("RGB", size, (245, 245, 240))
    d = ImageDraw.Draw(img)
    font = ImageFont.load_default(size=int(w * 0.44))
    d.text((w / 2, h * 0.3), year, fill=(10, 10, 10), font=font, anchor="mm")
    d.text((w / 2, h * 0.72), rest, fill=(10, 10, 10), font=font, anchor="mm")
    return np.asarray(img)


@register_asset(
    "labeled_can",
    footprint=0.035,
    role="task",
    family="can",
    randomize=lambda rng: {"rgba": _rgba(_color(rng, 0.2, 0.9))},
)
def add_labeled_can(
    spec,
    name,
    pos,
    yaw=0.0,
    label_kind: str = "date",
    date: str = "2024-06-01",
    label_color: str = "red",
    rgba=(0.8, 0.1, 0.1, 1),
):
    """A can (radius 0.0285 m) with an information label on a cylindrical arc of radius 0.029 m
    centred on the body's +x face: a colour on a 45 deg arc 3.6 cm high (paper: can-inspection
    assets), or a production date on a 100 deg arc 7 cm high (large enough to read at 512x384)."""
    if label_kind not in ("date", "color"):
        raise ValueError(f"label_kind must be 'date' or 'color', got {label_kind!r}")
    b = free_body(spec, name, pos, yaw)
    add_geom(b, mujoco.mjtGeom.mjGEOM_CYLINDER, (0.0285, 0.06, 0), (0, 0, 0.06), rgba, 0.3, f"{name}_body")
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (0.024, 0.003, 0),
        (0, 0, 0.123),
        (0.8, 0.8, 0.82, 1),
        collide=False,
    )
    if label_kind == "date":
        dt.date.fromisoformat(date)  # clear error on a malformed date
        img = date_label_image(date)
    else:
        if label_color not in MAT_COLORS:
            raise ValueError(f"unknown label colour {label_color!r}; choose from {sorted(MAT_COLORS)}")
        img = np.tile(np.asarray([int(255 * c) for c in MAT_COLORS[label_color]], np.uint8), (16, 16, 1))
    mat = add_texture_material(spec, f"{name}_label", img)
    (z0, z1), arc = ((0.018, 0.088), 100.0) if label_kind == "date" else ((0.042, 0.078), 45.0)
    arc_label(spec, name, f"{name}_label_mesh", mat, 0.029, z0, z1, arc_deg=arc)
    attributes = {"label_kind": label_kind}
    if label_kind == "date":
        attributes["production_date"] = date
    else:
        attributes["label_color"] = label_color
    functional = Functional(
        grasp=((0.0, 0.0, 0.095),),  # the palm clears the top
        info_face=InfoFace(f"{name}_label_mesh_geom", (0.029, 0.0, (z0 + z1) / 2), (1.0, 0.0, 0.0)),
    )
    return ObjectInfo(
        name, "labeled_can", name, (0.029, 0.029, 0.063), (0, 0, 0.063), 0.3, attributes, functional
    )
