"""Props of the first task set: desk bell, cup, coaster, numbered push button, gray block with a
hidden coloured back patch. Articulated parts use spring-loaded slide joints."""

from __future__ import annotations

import mujoco
import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..look.dress import dress
from . import dressing
from .base import ObjectInfo, add_geom, add_texture_material, free_body, static_body
from .functional import Functional, InfoFace, Press, Support
from .registry import register_asset

BLOCK_COLORS = {  # named colours shared by blocks, patches and pads
    "red": (0.85, 0.12, 0.1, 1),
    "green": (0.12, 0.7, 0.2, 1),
    "blue": (0.12, 0.3, 0.85, 1),
    "yellow": (0.95, 0.82, 0.1, 1),
    "purple": (0.55, 0.2, 0.7, 1),
    "orange": (0.95, 0.5, 0.1, 1),
}
GRAY = (0.55, 0.55, 0.56, 1)
NEUTRAL_PAD = (0.95, 0.95, 0.93, 1)
# Paper (App. "Button asset"): pressed below -0.005 m, reset above -0.001 m.
BUTTON_PRESSED, BUTTON_RESET, BUTTON_TRAVEL = -0.005, -0.001, 0.012
BELL_PRESSED = -0.004


def _spring_slide(body, name: str, travel: float, stiffness: float, damping: float):
    j = body.add_joint()
    j.name = name
    j.type = mujoco.mjtJoint.mjJNT_SLIDE
    j.axis = (0, 0, 1)
    j.range = (-travel, 0.0)
    j.limited = mujoco.mjtLimited.mjLIMITED_TRUE
    j.stiffness[0] = stiffness
    j.springref = 0.003  # preloaded against the upper limit: rests at exactly 0
    j.damping[0] = damping
    body.gravcomp = 1.0
    return j


@register_asset("bell", footprint=0.06, role="task")
def add_bell(
    spec, name, pos, yaw=0.0, radius=0.05, rgba=(0.85, 0.72, 0.25, 1), base_rgba=(0.15, 0.15, 0.16, 1)
):
    """Desk bell: heavy base, dome, spring-loaded plunger on top (``functional.press``). A gripper
    holds it around the dome, above the base (only a bell narrower than the default fits the open
    gripper: ``radius`` <= 0.045)."""
    b = free_body(spec, name, pos, yaw)
    base_mass = 0.45 * (radius / 0.05) ** 2
    base = add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius, 0.008, 0),
        (0, 0, 0.008),
        base_rgba,
        base_mass,
        f"{name}_body",
    )
    dome = add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_ELLIPSOID,
        (radius * 0.85, radius * 0.85, 0.035),
        (0, 0, 0.016),
        rgba,
        name=f"{name}_dome",
        collide=False,
    )
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (radius * 0.7, 0.014, 0),
        (0, 0, 0.03),
        rgba,
        0.05,
        f"{name}_dome_collision",
    ).group = 3
    stem = b.add_body()
    stem.name = f"{name}_plunger"
    stem.pos = (0, 0, 0.051)
    _spring_slide(stem, f"{name}_plunger_joint", 0.008, 300.0, 2.0)
    add_geom(
        stem,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (0.004, 0.006, 0),
        (0, 0, 0.006),
        (0.3, 0.3, 0.3, 1),
        0.005,
        f"{name}_stem",
    )
    add_geom(
        stem,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (0.012, 0.003, 0),
        (0, 0, 0.013),
        (0.2, 0.2, 0.2, 1),
        0.005,
        f"{name}_cap",
    )
    dress(spec, b, name, [base, dome], dressing.bell(radius, rgba, base_rgba))
    top = 0.067
    return ObjectInfo(
        name,
        "bell",
        name,
        (radius, radius, top / 2),
        (0, 0, top / 2),
        base_mass + 0.06,
        functional=Functional(
            press=Press((0.0, 0.0, top), f"{name}_plunger_joint", BELL_PRESSED), grasp=((0.0, 0.0, 0.047),)
        ),
    )


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


def digit_image(digit: str, size: int = 64) -> np.ndarray:
    """A black digit on a white square (PIL's bundled font, scaled)."""
    img = Image.new("RGB", (size, size), (245, 245, 245))
    draw = ImageDraw.Draw(img)
    font = ImageFont.load_default(size=int(size * 0.8))
    draw.text((size / 2, size / 2), str(digit), fill=(10, 10, 10), font=font, anchor="mm")
    return np.asarray(img)


@register_asset("button", footprint=0.07, role="task", static=True)
def add_button(spec, name, pos, yaw=0.0, number: int = 1, cap_rgba=(0.85, 0.15, 0.12, 1)):
    """Static push button with a spring-loaded cap (``functional.press``) and its number on a label
    plate in front of the cap (readable from the robot's side)."""
    b = static_body(spec, name, pos, yaw)
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.06, 0.04, 0.012),
        (0, 0, 0.012),
        (0.2, 0.2, 0.22, 1),
        None,
        f"{name}_body",
    )
    cap = b.add_body()
    cap.name = f"{name}_cap"
    cap.pos = (0.022, 0, 0.024)
    _spring_slide(cap, f"{name}_joint", BUTTON_TRAVEL, 80.0, 2.0)
    g = add_geom(
        cap,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        (0.021, 0.007, 0),
        (0, 0, 0.007),
        cap_rgba,
        0.01,
        f"{name}_cap_geom",
    )
    # The base is welded to the world, so parent filtering does not apply: the cap touches only the robot.
    g.contype, g.conaffinity = 0, 2
    mat = add_texture_material(spec, f"{name}_digit", digit_image(str(number)))
    # Number label on the base's top, on the robot's side of the cap (-x: the sampler yaws +x outward).
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.018, 0.018, 0.0005),
        (-0.031, 0.0, 0.0245),
        (1, 1, 1, 1),
        name=f"{name}_label",
        quat=_label_quat(),
        material=mat,
        collide=False,
    )
    return ObjectInfo(
        name,
        "button",
        name,
        (0.06, 0.04, 0.0155),
        (0, 0, 0.0155),
        0.0,
        {"number": int(number)},
        Functional(press=Press((0.022, 0.0, 0.038), f"{name}_joint", BUTTON_PRESSED, reset_at=BUTTON_RESET)),
    )


def _label_quat() -> np.ndarray:
    """Rotate the label's texture so the digit reads upright for a viewer on the body's -x side."""
    q = np.zeros(4)
    mujoco.mju_axisAngle2Quat(q, np.array([0.0, 0.0, 1.0]), -np.pi / 2)
    return q


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


@register_asset("color_pad", footprint=0.07, role="task", static=True)
def add_color_pad(spec, name, pos, yaw=0.0, color: str = "red", half: float = 0.06):
    """Thin static pad (placement target) in one of the block colours or ``'neutral'`` (white)."""
    colors = {**BLOCK_COLORS, "neutral": NEUTRAL_PAD}
    if color not in colors:
        raise ValueError(f"unknown pad colour {color!r}; choose from {sorted(colors)}")
    b = static_body(spec, name, pos, yaw)
    add_geom(
        b, mujoco.mjtGeom.mjGEOM_BOX, (half, half, 0.002), (0, 0, 0.002), colors[color], None, f"{name}_body"
    )
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
