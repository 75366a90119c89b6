"""Compact builders for multi-part objects: a list of primitive parts on one free (or static) body,
plus code-built meshes (cone, ring) and PIL label textures."""

from __future__ import annotations

import math

import mujoco
import numpy as np
from PIL import Image, ImageDraw, ImageFont

from .base import ObjectInfo, add_geom, add_texture_material, free_body, static_body
from .functional import Functional

KIND = {
    "box": mujoco.mjtGeom.mjGEOM_BOX,
    "cyl": mujoco.mjtGeom.mjGEOM_CYLINDER,
    "sph": mujoco.mjtGeom.mjGEOM_SPHERE,
    "cap": mujoco.mjtGeom.mjGEOM_CAPSULE,
    "ell": mujoco.mjtGeom.mjGEOM_ELLIPSOID,
    "mesh": mujoco.mjtGeom.mjGEOM_MESH,
}


def quat_axis_angle(axis, angle: float) -> np.ndarray:
    q = np.zeros(4)
    mujoco.mju_axisAngle2Quat(q, np.asarray(axis, float), float(angle))
    return q


def compound(
    spec,
    name: str,
    category: str,
    pos,
    yaw: float,
    parts: list[tuple],
    mass: float,
    static: bool = False,
    functional: Functional | None = None,
    attributes: dict | None = None,
) -> ObjectInfo:
    """``parts``: (kind, size, pos, rgba[, options]) with options ``quat``, ``visual`` (no collision),
    ``material``, ``mesh``. The first part is the main collision geom ``<name>_body``. Mass is spread
    over the colliding parts by volume; the bounding box is computed from the compiled parts."""
    body = static_body(spec, name, pos, yaw) if static else free_body(spec, name, pos, yaw)
    geoms = []
    for k, part in enumerate(parts):
        kind, size, ppos, rgba = part[:4]
        opt = part[4] if len(part) > 4 else {}
        g = add_geom(
            body,
            KIND[kind],
            size,
            ppos,
            rgba,
            name=f"{name}_body" if k == 0 else f"{name}_part{k}",
            quat=opt.get("quat"),
            material=opt.get("material"),
            collide=not opt.get("visual", False),
        )
        if kind == "mesh":
            g.meshname = opt["mesh"]
        geoms.append((g, opt.get("visual", False)))
    solid = [g for g, visual in geoms if not visual]
    vols = np.array([_volume(g) for g in solid])
    for g, v in zip(solid, vols, strict=True):
        g.mass = 0.0 if static else float(mass * v / vols.sum())
    lo, hi = _bbox(parts)
    half = tuple(float(x) for x in (hi - lo) / 2)
    center = tuple(float(x) for x in (hi + lo) / 2)
    return ObjectInfo(
        name,
        category,
        name,
        half,
        center,
        0.0 if static else mass,
        dict(attributes or {}),
        functional or Functional(),
    )


def _volume(g) -> float:
    s = np.asarray(g.size)
    t = g.type
    if t == mujoco.mjtGeom.mjGEOM_BOX:
        return 8 * s[0] * s[1] * s[2]
    if t == mujoco.mjtGeom.mjGEOM_CYLINDER:
        return 2 * math.pi * s[0] ** 2 * s[1]
    if t == mujoco.mjtGeom.mjGEOM_SPHERE:
        return 4 / 3 * math.pi * s[0] ** 3
    if t == mujoco.mjtGeom.mjGEOM_CAPSULE:
        return math.pi * s[0] ** 2 * (2 * s[1] + 4 / 3 * s[0])
    if t == mujoco.mjtGeom.mjGEOM_ELLIPSOID:
        return 4 / 3 * math.pi * s[0] * s[1] * s[2]
    return 1e-4  # meshes: nominal


def _extent(kind: str, size) -> np.ndarray:
    s = np.asarray(size, float)
    if kind == "box" or kind == "ell":
        return s[:3]
    if kind == "cyl":
        return np.array([s[0], s[0], s[1]])
    if kind == "sph":
        return np.array([s[0]] * 3)
    if kind == "cap":
        return np.array([s[0], s[0], s[1] + s[0]])
    return np.asarray(size[:3], float)  # meshes pass their half extents as size


def _bbox(parts) -> tuple[np.ndarray, np.ndarray]:
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for part in parts:
        kind, size, ppos = part[0], part[1], np.asarray(part[2], float)
        opt = part[4] if len(part) > 4 else {}
        e = _extent(kind, opt.get("extent", size))
        if opt.get("quat") is not None:
            rot = np.zeros(9)
            mujoco.mju_quat2Mat(rot, np.asarray(opt["quat"], float))
            e = np.abs(rot.reshape(3, 3)) @ e
        lo, hi = np.minimum(lo, ppos - e), np.maximum(hi, ppos + e)
    return lo, hi


def cone_mesh(spec, name: str, radius: float, height: float, n: int = 16) -> str:
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    verts = [[radius * math.cos(t), radius * math.sin(t), 0.0] for t in a] + [[0.0, 0.0, height]]
    mesh = spec.add_mesh()
    mesh.name = name
    mesh.uservert = np.asarray(verts, float).reshape(-1)
    return name


def text_texture(
    spec, name: str, text: str, bg=(240, 240, 235), fg=(20, 20, 20), size=(128, 64), fill: float = 0.42
) -> str:
    """A texture material with ``text`` written on it (for labels and boxes). ``fill``: font size
    as a fraction of the height, shrunk if the text would not fit 90 % of the width."""
    img = Image.new("RGB", size, bg)
    draw = ImageDraw.Draw(img)
    px = int(size[1] * fill)
    font = ImageFont.load_default(size=px)
    width = draw.textlength(text, font=font)
    if width > 0.9 * size[0]:
        font = ImageFont.load_default(size=max(8, int(px * 0.9 * size[0] / width)))
    draw.text((size[0] / 2, size[1] / 2), text, fill=fg, font=font, anchor="mm")
    return add_texture_material(spec, name, np.asarray(img))


def arc_label(
    spec,
    body_name: str,
    name: str,
    material: str,
    radius: float,
    z0: float,
    z1: float,
    arc_deg: float = 45.0,
    n: int = 8,
):
    """A visual-only curved label: a cylindrical strip of ``arc_deg`` centred on the body's +x side,
    texture u along the arc (left to right seen from outside), v up."""
    a = np.radians(np.linspace(-arc_deg / 2, arc_deg / 2, n + 1))  # left to right seen from outside (+x)
    verts, uv, faces = [], [], []
    for k, t in enumerate(a):
        for j, z in enumerate((z0, z1)):
            verts.append([radius * math.cos(t), radius * math.sin(t), z])
            uv.append([k / n, 1.0 - j])
    for k in range(n):
        b0, t0, b1, t1 = 2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3
        faces += [[b0, b1, t1], [b0, t1, t0]]  # counter-clockwise seen from outside
    mesh = spec.add_mesh()
    mesh.name = name
    mesh.uservert = np.asarray(verts, float).reshape(-1)
    mesh.usertexcoord = np.asarray(uv, float).reshape(-1)
    mesh.userface = np.asarray(faces, np.int32).reshape(-1)
    mesh.userfacetexcoord = np.asarray(faces, np.int32).reshape(-1)
    mesh.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL  # an open strip has no volume
    body = spec.body(body_name)
    g = add_geom(
        body,
        mujoco.mjtGeom.mjGEOM_MESH,
        (0, 0, 0),
        (0, 0, 0),
        (1, 1, 1, 1),
        name=f"{name}_geom",
        material=material,
        collide=False,
    )
    g.meshname = name
    return g
