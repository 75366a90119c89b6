"""Fan-shaped and two-level workspaces (paper App. "Fan-Shaped and Two-Level Workspaces").

The robot base sits at the world origin facing +y; angles are robot-centric, measured in the
horizontal plane from +x, so 90 deg is straight ahead. Tabletops are built from convex annular-sector
prisms, the collision surface; a scene hides them and shows a textured slab of the same outline
(``look/tabletop.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

WORLD_CONTYPE, WORLD_CONAFFINITY = 1, 1
TABLE_RGBA = (0.62, 0.52, 0.42, 1.0)
TABLE_TOP = 0.74  # m: height of the lower fan's top
COLLISION_ONLY_GROUP = 3  # geoms that collide but are not drawn (as the robot's collision shapes)


@dataclass(frozen=True)
class FanLevel:
    """One annular tabletop: radii (m), angular span centred at ``center_deg``, top height."""

    inner_radius: float
    outer_radius: float
    span_deg: float
    center_deg: float
    top_z: float
    thickness: float = 0.05

    @property
    def start_deg(self) -> float:
        return self.center_deg - self.span_deg / 2

    @property
    def end_deg(self) -> float:
        return self.center_deg + self.span_deg / 2


@dataclass(frozen=True)
class Workspace:
    """A lower fan plus an optional upper band; ``margin_deg`` keeps placements off the ends. The
    upper band stands on one square column (``column_half`` m half-width) at ``column_r`` m
    straight ahead of the upper band's centre."""

    levels: tuple[FanLevel, ...]
    margin_deg: float = 20.0
    column_half: float = 0.025
    column_r: float = 0.775

    @property
    def two_level(self) -> bool:
        return len(self.levels) > 1

    def level(self, index: int) -> FanLevel:
        if not 0 <= index < len(self.levels):
            raise ValueError(
                f"level {index} does not exist: this workspace has levels 0..{len(self.levels) - 1}"
            )
        return self.levels[index]

    def place(self, radius: float, angle_deg: float, level: int = 0) -> np.ndarray:
        """World position on a tabletop from robot-centric cylindrical coordinates."""
        lv = self.level(level)
        lo, hi = lv.start_deg + self.margin_deg, lv.end_deg - self.margin_deg
        if not lv.inner_radius <= radius <= lv.outer_radius:
            raise ValueError(
                f"radius {radius:.3f} m is off level {level} (annulus {lv.inner_radius}-{lv.outer_radius} m)"
            )
        if not lo - 1e-9 <= angle_deg <= hi + 1e-9:
            raise ValueError(
                f"angle {angle_deg:.1f} deg is outside level {level}'s placement span {lo:.0f}-{hi:.0f} deg "
                f"({self.margin_deg:.0f} deg margin at each end)"
            )
        a = math.radians(angle_deg)
        return np.array([radius * math.cos(a), radius * math.sin(a), lv.top_z])

    def placement_span_deg(self, level: int = 0) -> tuple[float, float]:
        lv = self.level(level)
        return lv.start_deg + self.margin_deg, lv.end_deg - self.margin_deg


def fan_workspace() -> Workspace:
    """The benchmark fan: annulus 0.30-1.08 m, 180 deg centred at 90 deg, top at 0.74 m."""
    return Workspace(levels=(FanLevel(0.30, 1.08, 180.0, 90.0, TABLE_TOP),))


UPPER_TOP = 1.09  # m: height of the upper band's top (0.35 m over the lower fan)


def two_level_workspace(shift_deg: float = 0.0) -> Workspace:
    """Lower fan plus the release's upper band, 0.60-0.80 m at 1.09 m (the paper says 0.90; the
    authors' release and our arms' reach use 0.80), on a 5 x 5 cm column at r 0.775 m straight
    ahead. ``shift_deg``: the paper's optional +/-20 deg turn of the upper band (the release's
    tasks use 0)."""
    if shift_deg not in (0.0, 20.0, -20.0):
        raise ValueError(f"shift_deg must be 0 or +/-20 (paper's two-level variant), got {shift_deg}")
    lower = FanLevel(0.30, 1.08, 180.0, 90.0, TABLE_TOP)
    upper = FanLevel(0.60, 0.80, 180.0, 90.0 + shift_deg, UPPER_TOP)
    return Workspace(levels=(lower, upper))


WORKSPACES = {"fan": fan_workspace, "two_level": two_level_workspace}  # a task's ``workspace`` name


def _sector_prism(r0: float, r1: float, a0: float, a1: float, z0: float, z1: float) -> np.ndarray:
    """Eight vertices of a convex annular-sector prism (angles in radians)."""
    pts = []
    for z in (z0, z1):
        for r, a in ((r0, a0), (r1, a0), (r1, a1), (r0, a1)):
            pts.append((r * math.cos(a), r * math.sin(a), z))
    return np.asarray(pts, dtype=float)


def add_level(
    spec: mujoco.MjSpec, lv: FanLevel, name: str, radial_segments: int, angular_segments: int
) -> int:
    """Tile one level with convex patches; returns the patch count."""
    body = spec.worldbody.add_body()
    body.name = name
    radii = np.linspace(lv.inner_radius, lv.outer_radius, radial_segments + 1)
    angles = np.radians(np.linspace(lv.start_deg, lv.end_deg, angular_segments + 1))
    n = 0
    for i in range(radial_segments):
        for k in range(angular_segments):
            verts = _sector_prism(
                radii[i], radii[i + 1], angles[k], angles[k + 1], lv.top_z - lv.thickness, lv.top_z
            )
            mesh = spec.add_mesh()
            mesh.name = f"{name}_patch_{i}_{k}"
            mesh.uservert = verts.reshape(-1)
            g = body.add_geom()
            g.type = mujoco.mjtGeom.mjGEOM_MESH
            g.meshname = mesh.name
            g.material = "tabletop"
            g.rgba = TABLE_RGBA
            g.contype, g.conaffinity = WORLD_CONTYPE, WORLD_CONAFFINITY
            g.friction = (1.0, 0.005, 0.0001)
            n += 1
    return n


def add_workspace(
    spec: mujoco.MjSpec, ws: Workspace, radial_segments: int = 2, angular_segments: int = 36
) -> None:
    """Add the tabletops, legs and (two-level) support column to ``spec``."""
    if "tabletop" not in [m.name for m in spec.materials]:
        mat = spec.add_material()
        mat.name = "tabletop"
        mat.rgba = TABLE_RGBA
    for idx, lv in enumerate(ws.levels):
        add_level(spec, lv, f"fan_level_{idx}", radial_segments, angular_segments)
    lower = ws.levels[0]
    legs = spec.worldbody.add_body()
    legs.name = "fan_legs"
    mid_r = 0.5 * (lower.inner_radius + lower.outer_radius)
    for a in np.radians(np.linspace(lower.start_deg + 10, lower.end_deg - 10, 4)):
        g = legs.add_geom()
        g.type = mujoco.mjtGeom.mjGEOM_CYLINDER
        g.size = (0.03, (lower.top_z - lower.thickness) / 2, 0)
        g.pos = (mid_r * math.cos(a), mid_r * math.sin(a), (lower.top_z - lower.thickness) / 2)
        g.rgba = (0.3, 0.3, 0.32, 1)
        g.contype = g.conaffinity = 0
    if ws.two_level:
        upper = ws.levels[1]
        a = math.radians(upper.center_deg)
        z0, z1 = lower.top_z, upper.top_z - upper.thickness
        col = spec.worldbody.add_body()
        col.name = "fan_support_column"
        col.pos = (ws.column_r * math.cos(a), ws.column_r * math.sin(a), (z0 + z1) / 2)
        col.quat = (math.cos(a / 2), 0.0, 0.0, math.sin(a / 2))  # faces the robot
        g = col.add_geom()
        g.name = "fan_support_column"
        g.type = mujoco.mjtGeom.mjGEOM_BOX
        g.size = (ws.column_half, ws.column_half, (z1 - z0) / 2)
        g.rgba = (0.35, 0.35, 0.38, 1)
        g.contype, g.conaffinity = WORLD_CONTYPE, WORLD_CONAFFINITY
