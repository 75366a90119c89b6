"""Devices operated in place, each with a working part on a joint: desk bell, numbered push button,
stapler (also picked and moved), rocker switch."""

from __future__ import annotations

import mujoco
import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..look.dress import dress
from . import dressing
from .base import ObjectInfo, add_geom, add_texture_material, free_body, static_body
from .functional import Functional, Press
from .parts import hinge, label_quat, random_rgb, spring_slide, with_alpha
from .registry import register_asset
from .shapes import quat_axis_angle

# Paper (App. "Button asset"): pressed below -0.005 m, reset above -0.001 m.
BUTTON_PRESSED, BUTTON_RESET, BUTTON_TRAVEL = -0.005, -0.001, 0.012


BELL_PRESSED = -0.004


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
    spring_slide(stem, f"{name}_plunger_joint", 0.008, 300.0, 2.0)
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
    base = add_geom(
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
    spring_slide(cap, f"{name}_joint", BUTTON_TRAVEL, 80.0, 2.0)
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
    base_look, cap_look = dressing.button(
        (0.06, 0.04), 0.024, 0.022, 0.021, 0.014, (0.2, 0.2, 0.22, 1), cap_rgba
    )
    dress(spec, b, name, [base], base_look)
    dress(spec, cap, f"{name}_cap", [g], cap_look)
    mat = add_texture_material(spec, f"{name}_digit", digit_image(str(number)))
    # Number label on the base's top, on the robot's side of the cap (-x: the sampler yaws +x outward).
    add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.018, 0.018, 0.0005),
        (-0.031, 0.0, 0.0245),
        (1, 1, 1, 1),
        name=f"{name}_label",
        quat=label_quat(),
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


STAPLER_OPEN = 0.14  # rad the top arm rests above closed


STAPLER_PRESSED = 0.1  # rad of travel that counts as a press (of 0.14)


@register_asset(
    "stapler", footprint=0.09, role="task", randomize=lambda rng: {"rgba": with_alpha(random_rgb(rng))}
)
def add_stapler(spec, name, pos, yaw=0.0, rgba=(0.1, 0.1, 0.12, 1)):
    """Desk stapler: base plate, rear post and a spring-loaded top arm hinged at the rear
    (``functional.press``'s joint: 0 = open, ``STAPLER_OPEN`` = pressed shut; press point at the front end
    of the arm, in the arm body's frame)."""
    b = free_body(spec, name, pos, yaw)
    plate = add_geom(
        b,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.075, 0.02, 0.006),
        (0, 0, 0.006),
        (0.15, 0.15, 0.16, 1),
        0.2,
        f"{name}_body",
    )
    post = add_geom(
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
    hinge(arm, f"{name}_joint", 0.0, STAPLER_OPEN, damping=0.05, stiffness=0.6, springref=-0.15)
    arm_geom = add_geom(
        arm, mujoco.mjtGeom.mjGEOM_BOX, (0.068, 0.017, 0.008), (0.066, 0, 0.0), rgba, 0.05, f"{name}_arm_geom"
    )
    base_look, arm_look = dressing.stapler(rgba, (0.15, 0.15, 0.16, 1))
    dress(spec, b, name, [plate, post], base_look)
    dress(spec, arm, f"{name}_arm", [arm_geom], arm_look)
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
    base = add_geom(
        b, mujoco.mjtGeom.mjGEOM_BOX, (0.045, 0.03, 0.012), (0, 0, 0.012), rgba, 0.45, f"{name}_body"
    )
    rocker = b.add_body()
    rocker.name = f"{name}_rocker"
    rocker.pos = (0, 0, 0.029)
    rocker.quat = quat_axis_angle([0, 1, 0], -SWITCH_TILT)  # +x end up: off
    rocker.gravcomp = 1.0
    hinge(rocker, f"{name}_joint", 0.0, SWITCH_ON, damping=0.02, frictionloss=0.01)
    rocker_geom = add_geom(
        rocker,
        mujoco.mjtGeom.mjGEOM_BOX,
        (0.038, 0.02, 0.005),
        (0, 0, 0),
        (0.8, 0.1, 0.1, 1),
        0.015,
        f"{name}_rocker_geom",
    )
    base_look, rocker_look = dressing.switch(
        (0.045, 0.03), 0.024, (0.038, 0.02, 0.005), rgba, (0.8, 0.1, 0.1, 1)
    )
    dress(spec, b, name, [base], base_look)
    dress(spec, rocker, f"{name}_rocker", [rocker_geom], rocker_look)
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
