"""The visible tabletop: one smooth annular-sector slab per level with flat-shaded faces and texture
coordinates in metres, so a wood or stone texture runs continuously across the whole fan. The
convex collision patches of ``sim/workspace.py`` stay as they are (hidden from the camera); this
mesh has the same outline and height, so what the camera sees is where contacts happen."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from ..workspace import FanLevel


def _quad_strip(a: np.ndarray, b: np.ndarray, normal, verts, normals, faces, flip: bool) -> None:
    """Two rows of points (a[k], b[k]) joined by quads with one flat normal."""
    start = sum(len(v) for v in verts)
    verts.append(np.concatenate([a, b]))
    normals.append(np.tile(np.asarray(normal, float), (2 * len(a), 1)))
    n = len(a)
    for k in range(n - 1):
        i, j, p, q = start + k, start + k + 1, start + n + k, start + n + k + 1
        faces += [(i, q, j), (i, p, q)] if flip else [(i, j, q), (i, q, p)]


def tabletop_mesh(lv: FanLevel, angular_segments: int = 36, radial_segments: int = 2):
    """Vertices (V, 3), triangles (F, 3), per-vertex normals (V, 3) and texture coordinates (V, 2,
    the world x, y in metres) of the level's slab: top, bottom, inner and outer rims, two ends.
    Faces wind counter-clockwise seen from outside. The default segments are the collision
    patches' (``workspace.add_workspace``), so the outline is exactly theirs."""
    z0, z1 = lv.top_z - lv.thickness, lv.top_z
    ang = np.radians(np.linspace(lv.start_deg, lv.end_deg, angular_segments + 1))
    radii = np.linspace(lv.inner_radius, lv.outer_radius, radial_segments + 1)
    verts, normals, faces = [], [], []

    def ring(r, z):
        return np.stack([r * np.cos(ang), r * np.sin(ang), np.full_like(ang, z)], axis=1)

    for i in range(radial_segments):  # top and bottom, ring by ring
        _quad_strip(ring(radii[i], z1), ring(radii[i + 1], z1), (0, 0, 1), verts, normals, faces, True)
        _quad_strip(ring(radii[i], z0), ring(radii[i + 1], z0), (0, 0, -1), verts, normals, faces, False)
    for k in range(angular_segments):  # rims: one flat normal per angular segment
        a = 0.5 * (ang[k] + ang[k + 1])
        out = (math.cos(a), math.sin(a), 0.0)
        seg = slice(k, k + 2)
        for r, normal, flip in (
            (lv.outer_radius, out, False),
            (lv.inner_radius, tuple(-c for c in out), True),
        ):
            lo, hi = ring(r, z0)[seg], ring(r, z1)[seg]
            _quad_strip(lo, hi, normal, verts, normals, faces, flip)
    for a, sign in ((ang[0], -1.0), (ang[-1], 1.0)):  # the two straight ends
        normal = (-sign * math.sin(a), sign * math.cos(a), 0.0)
        radial = np.array([[r * math.cos(a), r * math.sin(a)] for r in (lv.inner_radius, lv.outer_radius)])
        lo = np.column_stack([radial, [z0, z0]])
        hi = np.column_stack([radial, [z1, z1]])
        _quad_strip(lo, hi, normal, verts, normals, faces, sign > 0)
    v = np.concatenate(verts)
    return v, np.asarray(faces, np.int32), np.concatenate(normals), v[:, :2].copy()


def add_tabletop_visual(spec: mujoco.MjSpec, body: mujoco.MjsBody, lv: FanLevel, name: str, material: str):
    """Add the level's visible slab to ``body`` (no contacts, no mass)."""
    v, f, n, uv = tabletop_mesh(lv)
    mesh = spec.add_mesh()
    mesh.name = name
    mesh.uservert = v.reshape(-1)
    mesh.userface = f.reshape(-1)
    mesh.usernormal = n.reshape(-1)
    mesh.usertexcoord = uv.reshape(-1)
    g = body.add_geom()
    g.name = name
    g.type = mujoco.mjtGeom.mjGEOM_MESH
    g.meshname = name
    g.material = material
    g.contype = g.conaffinity = 0
    g.mass = 0.0
    g.group = 0
    return g
