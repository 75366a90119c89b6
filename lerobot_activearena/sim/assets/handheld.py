"""Objects the robot picks up: cup, gray block with a hidden coloured back patch, hammer, pill bottle,
Rubik's cube, wooden block, coffee box, food container, fan, mouse, shoe, seal, and a can with a rear
label (production date or colour)."""

from __future__ import annotations

import datetime as dt

import mujoco
import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..look.dress import dress
from ..look.textures import make_texture
from . import dressing
from .base import ObjectInfo, add_geom, add_texture_material, free_body
from .colors import BLOCK_COLORS, GRAY, MAT_COLORS
from .functional import Functional, InfoFace, ToolHead
from .parts import dress_parts, random_rgb, with_alpha
from .registry import register_asset
from .shapes import arc_label, compound, quat_axis_angle, text_texture


@register_asset(
    "cup",
    footprint=0.05,
    role="task",
    randomize=lambda rng: {"rgba": (*rng.uniform([0.5, 0.5, 0.5], [0.98, 0.98, 0.98]), 1.0)},
)
def add_cup(spec, name, pos, yaw=0.0, radius=0.034, height=0.09, rgba=(0.9, 0.9, 0.92, 1)):
    """Cup: cylinder body, dark inside disc at the rim (reads as empty), side handle."""
    b = free_body(spec, name, pos, yaw)
    shell = add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius, height / 2, 0),
        (0, 0, height / 2),
        rgba,
        0.12,
        f"{name}_body",
    )
    inside = add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius * 0.85, 0.0008, 0),
        (0, 0, height),
        (0.25, 0.22, 0.2, 1),
        collide=False,
    )
    dress(spec, b, name, [shell, inside], dressing.cup(radius, height, rgba))
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        (0.006, 0.022, 0),
        (-radius - 0.012, 0, height * 0.55),
        rgba,
        collide=False,
    )
    return ObjectInfo(name, "cup", name, (radius + 0.018, radius, height / 2), (-0.009, 0, height / 2), 0.12)


@register_asset("patch_block", footprint=0.036, role="task")
def add_patch_block(spec, name, pos, yaw=0.0, patch_color: str = "red"):
    """Gray block (half 0.024 m) with a thin coloured patch on its +x face (half (0.0015, 0.012,
    0.012) m, protruding 0.00005 m), as in the paper's check-color assets."""
    if patch_color not in BLOCK_COLORS:
        raise ValueError(f"unknown patch colour {patch_color!r}; choose from {sorted(BLOCK_COLORS)}")
    h = 0.024
    b = free_body(spec, name, pos, yaw)
    add_geom(b, mujoco.mjtGeom.mjGEOM_BOX, (h, h, h), (0, 0, h), GRAY, 0.08, f"{name}_body")
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.0015, 0.012, 0.012),
        (h + 0.00005 - 0.0015, 0, h),
        BLOCK_COLORS[patch_color],
        name=f"{name}_patch",
        collide=False,
    )
    return ObjectInfo(
        name,
        "patch_block",
        name,
        (h, h, h),
        (0, 0, h),
        0.08,
        {"patch_color": patch_color},
        Functional(info_face=InfoFace(f"{name}_patch", (h, 0.0, h), (1.0, 0.0, 0.0))),
    )


@register_asset(
    "hammer", footprint=0.11, role="task", randomize=lambda rng: {"handle": random_rgb(rng, 0.3, 0.9)}
)
def add_hammer(spec, name, pos, yaw=0.0, handle=(0.6, 0.4, 0.2)):
    info = compound(
        spec,
        name,
        "hammer",
        pos,
        yaw,
        [
            ("box", (0.1, 0.012, 0.012), (0.0, 0, 0.012), with_alpha(handle)),
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
    dress_parts(spec, name, range(2), dressing.hammer(with_alpha(handle), (0.3, 0.3, 0.33, 1)))
    return info


@register_asset(
    "pill_bottle",
    footprint=0.03,
    role="task",
    randomize=lambda rng: {"rgba": with_alpha(random_rgb(rng, 0.5, 0.95))},
)
def add_pill_bottle(spec, name, pos, yaw=0.0, rgba=(0.95, 0.6, 0.15, 1)):
    info = compound(
        spec,
        name,
        "pill_bottle",
        pos,
        yaw,
        [
            ("cyl", (0.022, 0.035, 0), (0, 0, 0.035), with_alpha(rgba[:3], 1.0)),
            ("cyl", (0.024, 0.009, 0), (0, 0, 0.079), (0.95, 0.95, 0.95, 1)),
            ("cyl", (0.0225, 0.012, 0), (0, 0, 0.035), (0.97, 0.97, 0.97, 1), {"visual": True}),
        ],
        0.08,
    )
    dress_parts(spec, name, range(2), dressing.pill_bottle(with_alpha(rgba[:3], 1.0)))
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


@register_asset(
    "container",
    footprint=0.06,
    role="task",
    randomize=lambda rng: {"lid": with_alpha(random_rgb(rng, 0.2, 0.9))},
)
def add_container(spec, name, pos, yaw=0.0, lid=(0.2, 0.6, 0.3, 1)):
    tub = (0.92, 0.92, 0.9, 0.95)
    info = compound(
        spec,
        name,
        "container",
        pos,
        yaw,
        [
            ("box", (0.045, 0.035, 0.025), (0, 0, 0.025), tub),
            ("box", (0.045, 0.035, 0.005), (0, 0, 0.055), lid),  # flush: an overhang caught the pads
        ],
        0.12,
    )
    dress_parts(spec, name, range(2), dressing.food_container(0.045, 0.035, 0.05, 0.01, tub, lid))
    return info


YAXIS_90 = quat_axis_angle([0, 1, 0], np.pi / 2)


@register_asset(
    "fan", footprint=0.08, role="task", randomize=lambda rng: {"rgba": with_alpha(random_rgb(rng, 0.2, 0.95))}
)
def add_fan(spec, name, pos, yaw=0.0, rgba=(0.2, 0.5, 0.85, 1)):
    """Desk fan: base, stand, a motor housing over the base behind a round guard that faces the
    body's -x side (the front), hub. Grasped across the housing above the base, near the centre of
    mass (the guard stays 2.8 cm clear of the fingers)."""
    dark = (0.2, 0.2, 0.22, 1)
    info = compound(
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
    dress_parts(spec, name, (0, 2, 3), dressing.fan(rgba, dark))
    return info


XAXIS_90 = quat_axis_angle([1, 0, 0], np.pi / 2)


@register_asset(
    "mouse",
    footprint=0.045,
    role="task",
    randomize=lambda rng: {"rgba": with_alpha(random_rgb(rng, 0.05, 0.9))},
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
    dress_parts(spec, name, range(1), dressing.mouse(rgba))
    return info


@register_asset(
    "shoe", footprint=0.08, role="task", randomize=lambda rng: {"rgba": with_alpha(random_rgb(rng, 0.1, 0.9))}
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
    dress_parts(spec, name, range(3), dressing.shoe(rgba))
    return info


@register_asset(
    "seal", footprint=0.04, role="task", randomize=lambda rng: {"rgba": with_alpha(random_rgb(rng, 0.2, 0.9))}
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
    dress_parts(spec, name, (1, 2), dressing.seal_handle(rgba))
    return info


DATE_RANGE = (dt.date(2023, 1, 1), dt.date(2026, 12, 31))  # paper: production dates


SHELF_LIFE_DAYS = 365


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
    randomize=lambda rng: {"rgba": with_alpha(random_rgb(rng, 0.2, 0.9))},
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
