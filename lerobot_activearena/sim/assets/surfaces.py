"""What objects are set down on or in: coaster, coloured pads, named-colour mats, plate, display
stand, electronic scale, plastic box, bread basket."""

from __future__ import annotations

import mujoco
import numpy as np

from ..look.dress import dress
from . import dressing
from .base import ObjectInfo, add_geom, add_texture_material, free_body, static_body
from .colors import BLOCK_COLORS, MAT_COLORS, NEUTRAL_PAD
from .functional import Container, Functional, Support
from .parts import dress_parts, open_box, random_rgb, with_alpha
from .registry import register_asset
from .shapes import compound, quat_axis_angle, text_texture


@register_asset(
    "coaster",
    footprint=0.055,
    role="task",
    randomize=lambda rng: {"rgba": tuple(BLOCK_COLORS[rng.choice(["orange", "purple", "blue"])])},
)
def add_coaster(spec, name, pos, yaw=0.0, radius=0.052, rgba=(0.55, 0.2, 0.7, 1)):
    b = free_body(spec, name, pos, yaw)
    disc = add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius, 0.003, 0),
        (0, 0, 0.003),
        rgba,
        0.06,
        f"{name}_body",
        friction=(1.2, 0.01, 0.001),
    )
    dress(spec, b, name, [disc], dressing.coaster(radius, rgba))
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius * 0.8, 0.0004, 0),
        (0, 0, 0.0062),
        (0.9, 0.88, 0.8, 1),
        collide=False,
    )
    return ObjectInfo(
        name,
        "coaster",
        name,
        (radius, radius, 0.003),
        (0, 0, 0.003),
        0.06,
        functional=Functional(support=Support(0.006, (radius, radius), "disc")),
    )


@register_asset("color_pad", footprint=0.07, role="task", static=True)
def add_color_pad(spec, name, pos, yaw=0.0, color: str = "red", half: float = 0.06):
    """Thin static pad (placement target) in one of the block colours or ``'neutral'`` (white)."""
    colors = {**BLOCK_COLORS, "neutral": NEUTRAL_PAD}
    if color not in colors:
        raise ValueError(f"unknown pad colour {color!r}; choose from {sorted(colors)}")
    b = static_body(spec, name, pos, yaw)
    slab = add_geom(
        b, mujoco.mjtGeom.mjGEOM_BOX, (half, half, 0.002), (0, 0, 0.002), colors[color], None, f"{name}_body"
    )
    dress(spec, b, name, [slab], dressing.pad(half, half, 0.004, colors[color]))
    return ObjectInfo(
        name,
        "color_pad",
        name,
        (half, half, 0.002),
        (0, 0, 0.002),
        0.0,
        {"color": color},
        Functional(support=Support(0.004, (half, half))),
    )


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
    slab = add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_BOX,
        (*half, 0.002),
        (0, 0, 0.002),
        with_alpha(MAT_COLORS[color_name]),
        None,
        f"{name}_body",
    )
    dress(spec, b, name, [slab], dressing.pad(*half, 0.004, with_alpha(MAT_COLORS[color_name])))
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


@register_asset(
    "plate",
    footprint=0.1,
    role="task",
    randomize=lambda rng: {"rgba": with_alpha(random_rgb(rng, 0.7, 0.98))},
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
    dress_parts(spec, name, range(3), dressing.plate(rgba))
    return info


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
    dress_parts(spec, name, range(3), dressing.display_stand(rgba))
    return info


@register_asset("electronic_scale", footprint=0.08, role="task")
def add_electronic_scale(spec, name, pos, yaw=0.0):
    mat = text_texture(spec, f"{name}_display", "0.00 g", bg=(40, 70, 50), fg=(120, 255, 140), size=(96, 48))
    info = compound(
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
    dress_parts(spec, name, range(1), dressing.electronic_scale((0.075, 0.065), 0.024, (0.82, 0.83, 0.85, 1)))
    return info


@register_asset(
    "plastic_box",
    footprint=0.11,
    role="task",
    randomize=lambda rng: {"rgba": with_alpha(random_rgb(rng, 0.3, 0.9), 1.0)},
)
def add_plastic_box(spec, name, pos, yaw=0.0, rgba=(0.3, 0.55, 0.85, 1)):
    info = compound(
        spec,
        name,
        "plastic_box",
        pos,
        yaw,
        open_box(rgba, (0.16, 0.12), 0.006, 0.07),
        0.2,
        functional=Functional(container=Container(0.006, (0.08, 0.06), 0.07)),
    )
    dress_parts(spec, name, range(5), dressing.open_box(0.086, 0.066, 0.006, 0.07, rgba))
    return info


@register_asset("bread_basket", footprint=0.11, role="task")
def add_bread_basket(spec, name, pos, yaw=0.0, rgba=(0.62, 0.42, 0.2, 1)):
    info = compound(
        spec,
        name,
        "bread_basket",
        pos,
        yaw,
        open_box(rgba, (0.17, 0.12), 0.008, 0.05),
        0.2,
        functional=Functional(container=Container(0.008, (0.085, 0.06), 0.05)),
    )
    # texture coordinates are metres: one 64-px tile (4 cells of 3 strands) every 6 cm
    weave = add_texture_material(spec, f"{name}_weave", dressing.basket_weave(rgba), texrepeat=(16, 16))
    look = dressing.open_box(0.093, 0.068, 0.008, 0.05, (1, 1, 1, 1), corner=0.03, material=weave)
    dress_parts(spec, name, range(5), look)
    return info
