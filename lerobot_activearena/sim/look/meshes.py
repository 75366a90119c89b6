"""Meshes made by code for what objects look like: lathed (bottles, cups, cans, bells, bowls) and
extruded (a mouse, a stapler, a shoe sole) shapes, with normals and texture coordinates.

``lathe`` texture coordinates wrap once around (u: angle, v: along the profile), so a label image
wraps a can or a bottle; ``extrude`` maps the caps by x, y in metres and the walls by perimeter
length and height. Edges sharper than ``crease_deg`` are shaded flat, the rest smooth.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np


@dataclass(frozen=True)
class MeshData:
    vertices: np.ndarray  # (V, 3) m
    faces: np.ndarray  # (F, 3) counter-clockwise seen from outside
    normals: np.ndarray  # (V, 3) unit
    texcoords: np.ndarray  # (V, 2)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.vertices.min(axis=0), self.vertices.max(axis=0)

    def volume(self) -> float:
        a, b, c = (self.vertices[self.faces[:, k]] for k in range(3))
        return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(n > 0, n, 1.0)


def lathe(profile, segments: int = 32, crease_deg: float = 40.0) -> MeshData:
    """Revolve ``profile`` [(r, z), ...] (from the bottom, r >= 0, ending on the axis to close the
    shape) around the z axis."""
    prof = np.asarray(profile, float)
    if prof.ndim != 2 or prof.shape[1] != 2 or len(prof) < 2 or np.any(prof[:, 0] < 0):
        raise ValueError("profile must be at least two (r, z) points with r >= 0")
    seg = np.diff(prof, axis=0)
    length = np.linalg.norm(seg, axis=1)
    if np.any(length <= 0):
        raise ValueError("profile has repeated points")
    # outward normal of each profile segment in the (r, z) plane (profile runs bottom -> top)
    seg_n = _unit(np.stack([seg[:, 1], -seg[:, 0]], axis=1))
    v_coord = np.concatenate([[0.0], np.cumsum(length)]) / length.sum()
    cos_crease = math.cos(math.radians(crease_deg))
    theta = np.linspace(0.0, 2 * np.pi, segments + 1)
    cos_t, sin_t = np.cos(theta), np.sin(theta)
    verts, normals, uvs, faces = [], [], [], []
    for k in range(len(seg)):
        rows = []
        for end in (k, k + 1):  # this segment's two rings, normals smoothed across gentle joints
            nb = k - 1 if end == k else k + 1
            n = seg_n[k]
            if 0 <= nb < len(seg) and seg_n[k] @ seg_n[nb] >= cos_crease:
                n = _unit(seg_n[k] + seg_n[nb])
            r, z = prof[end]
            start = sum(len(v) for v in verts)
            verts.append(np.stack([r * cos_t, r * sin_t, np.full_like(theta, z)], axis=1))
            normals.append(np.stack([n[0] * cos_t, n[0] * sin_t, np.full_like(theta, n[1])], axis=1))
            uvs.append(np.stack([theta / (2 * np.pi), np.full_like(theta, v_coord[end])], axis=1))
            rows.append((start, r))
        (a, ra), (b, rb) = rows
        for j in range(segments):
            if ra > 0:
                faces.append((a + j, a + j + 1, b + j + 1))
            if rb > 0:
                faces.append((a + j, b + j + 1, b + j))
    return MeshData(
        np.concatenate(verts),
        np.asarray(faces, np.int32),
        _unit(np.concatenate(normals)),
        np.concatenate(uvs),
    )


def scaled(mesh: MeshData, sx: float, sy: float, sz: float = 1.0) -> MeshData:
    """``mesh`` stretched along its axes (a lathed dome becomes an oval one: a mouse, a shoe's
    upper); normals follow the inverse transpose, texture coordinates stay."""
    if min(sx, sy, sz) <= 0:
        raise ValueError(f"scale factors must be > 0, got {(sx, sy, sz)}")
    s = np.array([sx, sy, sz])
    return MeshData(mesh.vertices * s, mesh.faces, _unit(mesh.normals / s), mesh.texcoords)


def rotated(mesh: MeshData, axis, angle: float) -> MeshData:
    """``mesh`` turned by ``angle`` (rad) about ``axis`` through the origin (a lathed handle laid
    along x); normals turn with it, texture coordinates stay."""
    axis = _unit(np.asarray(axis, float))
    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    rot = np.eye(3) * c + s * k + (1 - c) * np.outer(axis, axis)
    return MeshData(mesh.vertices @ rot.T, mesh.faces, _unit(mesh.normals @ rot.T), mesh.texcoords)


def _triangulate(poly: np.ndarray) -> list[tuple[int, int, int]]:
    """Ear clipping of a simple counter-clockwise polygon."""
    idx = list(range(len(poly)))
    tris = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    guard = 0
    while len(idx) > 3 and guard < 10 * len(poly) ** 2:
        guard += 1
        for k in range(len(idx)):
            i, j, m = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            if cross(poly[i], poly[j], poly[m]) <= 1e-15:
                continue  # reflex or flat corner
            if any(
                cross(poly[i], poly[j], poly[p]) >= 0
                and cross(poly[j], poly[m], poly[p]) >= 0
                and cross(poly[m], poly[i], poly[p]) >= 0
                for p in idx
                if p not in (i, j, m)
            ):
                continue  # another vertex inside the ear
            tris.append((i, j, m))
            idx.pop(k)
            break
        else:
            raise ValueError("polygon is not simple or not counter-clockwise")
    tris.append(tuple(idx))
    return tris


def extrude(outline, height: float, crease_deg: float = 40.0) -> MeshData:
    """Extrude a simple counter-clockwise outline [(x, y), ...] (m) from z = 0 to ``height``."""
    poly = np.asarray(outline, float)
    area = 0.5 * np.sum(poly[:, 0] * np.roll(poly[:, 1], -1) - np.roll(poly[:, 0], -1) * poly[:, 1])
    if len(poly) < 3 or area <= 0:
        raise ValueError("outline must be at least three points, counter-clockwise")
    if height <= 0:
        raise ValueError(f"height must be > 0, got {height}")
    n = len(poly)
    edge = np.roll(poly, -1, axis=0) - poly
    edge_len = np.linalg.norm(edge, axis=1)
    edge_n = _unit(np.stack([edge[:, 1], -edge[:, 0]], axis=1))
    cos_crease = math.cos(math.radians(crease_deg))
    perim = np.concatenate([[0.0], np.cumsum(edge_len)])
    verts, normals, uvs, faces = [], [], [], []
    for k in range(n):  # walls: one quad per edge
        k1 = (k + 1) % n
        ns = []
        for nb in (k - 1, k1):  # smooth with the neighbouring edge unless a crease
            nb %= n
            ns.append(_unit(edge_n[k] + edge_n[nb]) if edge_n[k] @ edge_n[nb] >= cos_crease else edge_n[k])
        start = sum(len(v) for v in verts)
        pts = [poly[k], poly[k1], poly[k1], poly[k]]
        zs = [0.0, 0.0, height, height]
        verts.append(np.array([[p[0], p[1], z] for p, z in zip(pts, zs, strict=True)]))
        normals.append(np.array([[*ns[i], 0.0] for i in (0, 1, 1, 0)]))
        uvs.append(np.array([[perim[k], 0], [perim[k + 1], 0], [perim[k + 1], height], [perim[k], height]]))
        faces += [(start, start + 1, start + 2), (start, start + 2, start + 3)]
    tris = _triangulate(poly)
    for z, sign in ((height, 1.0), (0.0, -1.0)):  # caps
        start = sum(len(v) for v in verts)
        verts.append(np.column_stack([poly, np.full(n, z)]))
        normals.append(np.tile([0.0, 0.0, sign], (n, 1)))
        uvs.append(poly.copy())
        faces += [
            (start + a, start + b, start + c) if sign > 0 else (start + a, start + c, start + b)
            for a, b, c in tris
        ]
    return MeshData(
        np.concatenate(verts),
        np.asarray(faces, np.int32),
        _unit(np.concatenate(normals)),
        np.concatenate(uvs),
    )


def add_visual_mesh(
    spec: mujoco.MjSpec,
    body: mujoco.MjsBody,
    name: str,
    mesh: MeshData,
    pos=(0.0, 0.0, 0.0),
    quat=(1.0, 0.0, 0.0, 0.0),
    rgba=(1.0, 1.0, 1.0, 1.0),
    material: str | None = None,
    group: int = 0,
) -> mujoco.MjsGeom:
    """Hang ``mesh`` on ``body`` as a visual-only geom (no contacts, no mass)."""
    m = spec.add_mesh()
    m.name = name
    m.uservert = mesh.vertices.reshape(-1)
    m.userface = mesh.faces.reshape(-1)
    m.usernormal = mesh.normals.reshape(-1)
    m.usertexcoord = mesh.texcoords.reshape(-1)
    g = body.add_geom()
    g.name = name
    g.type = mujoco.mjtGeom.mjGEOM_MESH
    g.meshname = name
    g.pos, g.quat, g.rgba = pos, quat, rgba
    if material:
        g.material = material
    g.contype = g.conaffinity = 0
    g.mass = 0.0
    g.group = group
    return g
