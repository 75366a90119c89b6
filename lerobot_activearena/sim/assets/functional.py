"""Functional metadata of an asset: what tasks, predicates and the expert know about an object
beyond its bounding box. Where it supports other objects, holds them, is grasped, is pressed,
strikes with, faces, or carries hidden information. Every point and size is in the object's body
frame (origin at its bottom centre, metres).

An asset declares these on its ``ObjectInfo.functional``; ``validate`` checks them against the
object's box when the asset is built, and ``missing_names`` against the compiled model.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

Vec3 = tuple[float, float, float]
SHAPES = ("box", "disc")


@dataclass(frozen=True)
class Support:
    """A top surface other objects rest on: a pad, a mat, a plate, a scale's platform."""

    top: float  # height of the surface above the origin
    half: tuple[float, float]  # half sizes of a box top; (radius, radius) of a disc
    shape: Literal["box", "disc"] = "box"


@dataclass(frozen=True)
class Container:
    """An open box or basket: objects inside rest over its floor and below its rim."""

    floor: float  # inner floor height above the origin
    inner_half: tuple[float, float]  # inner half sizes (x, y)
    rim: float  # rim height above the origin


@dataclass(frozen=True)
class Press:
    """A press point and what it moves: the press counts when ``joint`` passes ``pressed_at``
    (below it for a plunger or a cap, above it for a stapler's arm or a rocker)."""

    point: Vec3  # where the fingertips press, in the frame of ``body`` (a cap may stand above the box)
    joint: str
    pressed_at: float
    direction: Literal["below", "above"] = "below"
    body: str | None = None  # the moving part the point is on (None: the object's own body)
    reset_at: float | None = None  # a spring-back joint is released again past this value

    def is_pressed(self, q: float) -> bool:
        return q < self.pressed_at if self.direction == "below" else q >= self.pressed_at


@dataclass(frozen=True)
class ToolHead:
    """The striking part of a tool (a hammer's head)."""

    point: Vec3  # centre of the head
    half: Vec3  # half sizes of the head's box


@dataclass(frozen=True)
class InfoFace:
    """A surface that carries task information (a colour patch, a date label)."""

    geom: str
    center: Vec3
    normal: Vec3  # outward unit normal


@dataclass(frozen=True)
class Functional:
    support: Support | None = None
    container: Container | None = None
    grasp: tuple[Vec3, ...] = ()  # where a gripper closes on it, preferred first
    grasp_axis: Vec3 | None = None  # the body axis the fingers close along (None: the expert picks)
    press: Press | None = None
    tool_head: ToolHead | None = None
    front: Vec3 | None = None  # the direction its front faces (a fan's airflow), unit
    info_face: InfoFace | None = None

    def validate(self, obj: str, half_extents, center_offset) -> None:
        """Raise ValueError naming the asset and the field when a declaration cannot be right for
        an object with this bounding box (half extents and centre offset, body frame)."""
        half, centre = np.asarray(half_extents, float), np.asarray(center_offset, float)
        lo, hi = centre - half - 1e-6, centre + half + 1e-6
        bottom, top = lo[2], hi[2]

        def inside(what: str, p) -> None:
            p = np.asarray(p, float)
            if p.shape != (3,) or not np.all((p >= lo) & (p <= hi)):
                raise ValueError(f"{obj}: {what} {tuple(p)} lies outside its bounding box {lo} .. {hi}")

        def problem(msg: str) -> None:
            raise ValueError(f"{obj}: {msg}")

        if self.support is not None:
            s = self.support
            if s.shape not in SHAPES:
                problem(f"support shape must be one of {SHAPES}, got {s.shape!r}")
            if not bottom <= s.top <= top:
                problem(f"support top {s.top} m is outside its height {bottom:.3f} .. {top:.3f}")
            if min(s.half) <= 0 or np.any(np.asarray(s.half) > half[:2] + 1e-6):
                problem(f"support half sizes {s.half} must be positive and within the box {half[:2]}")
        if self.container is not None:
            c = self.container
            if not bottom <= c.floor < c.rim <= top:
                problem(f"container needs floor < rim within the height: floor {c.floor}, rim {c.rim}")
            if min(c.inner_half) <= 0 or np.any(np.asarray(c.inner_half) > half[:2]):
                problem(f"container inner half sizes {c.inner_half} must fit inside the box {half[:2]}")
        for k, p in enumerate(self.grasp):
            inside(f"grasp point {k}", p)
        if self.grasp_axis is not None and abs(np.linalg.norm(self.grasp_axis) - 1.0) > 1e-6:
            problem(f"grasp axis {self.grasp_axis} must be a unit vector")
        if self.press is not None:
            if self.press.direction not in ("below", "above"):
                problem(f"press direction must be 'below' or 'above', got {self.press.direction!r}")
            if np.asarray(self.press.point, float).shape != (3,):
                problem(f"press point {self.press.point} must be a 3-D point")
        if self.tool_head is not None:
            inside("tool head", self.tool_head.point)
        if self.front is not None and abs(np.linalg.norm(self.front) - 1.0) > 1e-6:
            problem(f"front {self.front} must be a unit vector")
        if self.info_face is not None:
            inside("information face centre", self.info_face.center)
            if abs(np.linalg.norm(self.info_face.normal) - 1.0) > 1e-6:
                problem(f"information face normal {self.info_face.normal} must be a unit vector")

    def model_names(self) -> list[tuple[str, str]]:
        """(kind, name) of every model element it refers to: joints, bodies, geoms."""
        out = []
        if self.press is not None:
            out.append(("joint", self.press.joint))
            if self.press.body is not None:
                out.append(("body", self.press.body))
        if self.info_face is not None:
            out.append(("geom", self.info_face.geom))
        return out

    def missing_names(self, model) -> list[str]:
        """The referred joints, bodies and geoms the compiled model lacks."""
        missing = []
        for kind, name in self.model_names():
            try:
                getattr(model, kind)(name)
            except KeyError:
                missing.append(f"{kind} {name!r}")
        return missing
