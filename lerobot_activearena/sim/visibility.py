"""Per-object visibility in a camera: in-image fraction of the projected bounding box, times the
unoccluded fraction of the object's surface samples (depth-aware ray casts with ``mj_multiRay``).

An object is visible when ``visible_fraction = in_image x unoccluded >= 0.4`` (paper: at least 40 %
of the projected bounding-box area inside the image and not occluded). Surface samples on the far
side of the object count as unoccluded when the first thing the ray hits is the object itself (or a
part attached to it).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from .assets.base import ObjectInfo
from .camera import extrinsic_cv, intrinsics, project

VISIBLE_THRESHOLD = 0.4
SAMPLES_PER_GEOM = 26
# Rays hit objects' shapes, the robot's visual geoms and the room, never a dressed look's meshes
# (look/dress.py), so what counts as visible does not depend on how things are drawn.
_RAY_GROUPS = np.array([1, 1, 1, 0, 0, 0], dtype=np.uint8)
_CUBE = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)


@dataclass
class Visibility:
    visible: np.ndarray  # (N,) bool
    visible_fraction: np.ndarray  # (N,) in [0, 1]
    in_image_fraction: np.ndarray
    unoccluded_fraction: np.ndarray
    uv_norm: (
        np.ndarray
    )  # (N, 2), centre of the in-image part of the projected bbox / (W, H); (-1, -1) when not visible


def _fibonacci_sphere(n: int) -> np.ndarray:
    i = np.arange(n) + 0.5
    phi = np.arccos(1 - 2 * i / n)
    theta = np.pi * (1 + 5**0.5) * i
    return np.stack([np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)], axis=1)


def geom_surface_samples(model: mujoco.MjModel, gid: int, n: int = SAMPLES_PER_GEOM) -> np.ndarray:
    """Points on a geom's surface, in the geom frame."""
    t, size = int(model.geom_type[gid]), model.geom_size[gid]
    if t == int(mujoco.mjtGeom.mjGEOM_BOX):
        d = _fibonacci_sphere(n)
        return d / np.max(np.abs(d) / size, axis=1, keepdims=True)
    if t == int(mujoco.mjtGeom.mjGEOM_SPHERE):
        return _fibonacci_sphere(n) * size[0]
    if t == int(mujoco.mjtGeom.mjGEOM_ELLIPSOID):
        return _fibonacci_sphere(n) * size
    if t in (int(mujoco.mjtGeom.mjGEOM_CYLINDER), int(mujoco.mjtGeom.mjGEOM_CAPSULE)):
        r, h = size[0], size[1]
        ring = np.linspace(0, 2 * np.pi, 8, endpoint=False)
        pts = [[0, 0, h], [0, 0, -h]]
        for z in (-h, 0.0, h):
            pts += [[r * np.cos(a), r * np.sin(a), z] for a in ring]
        return np.asarray(pts, float)
    if t == int(mujoco.mjtGeom.mjGEOM_MESH):
        mid = model.geom_dataid[gid]
        start, count = model.mesh_vertadr[mid], model.mesh_vertnum[mid]
        verts = model.mesh_vert[start : start + count]
        step = max(1, count // n)
        return np.asarray(verts[::step][:n], float)
    raise ValueError(f"no surface sampler for geom type {t} (geom {gid})")


class VisibilityChecker:
    """Precomputes surface samples of registered objects; evaluates visibility per frame."""

    def __init__(
        self,
        model: mujoco.MjModel,
        objects: list[ObjectInfo],
        camera: str,
        width: int,
        height: int,
        exclude_body: str | None = None,
    ):
        self.model = model
        self.objects = objects
        self.cam_id = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, camera)
        if self.cam_id < 0:
            raise ValueError(f"camera {camera!r} is not in the model")
        self.width, self.height = width, height
        self.K = intrinsics(float(model.cam_fovy[self.cam_id]), width, height)
        self.exclude_body = -1 if exclude_body is None else model.body(exclude_body).id
        geoms, local, owner = [], [], []
        self.body_ids = []
        for k, obj in enumerate(objects):
            bid = model.body(obj.body).id
            self.body_ids.append(bid)
            for gid in np.flatnonzero(model.geom_bodyid == bid):
                if model.geom_group[gid] > 2 or model.geom_rgba[gid, 3] == 0:
                    continue
                pts = geom_surface_samples(model, gid)
                geoms.append(np.full(len(pts), gid))
                local.append(pts)
                owner.append(np.full(len(pts), k))
        self._geom = np.concatenate(geoms) if geoms else np.zeros(0, int)
        self._local = np.concatenate(local) if local else np.zeros((0, 3))
        self._owner = np.concatenate(owner) if owner else np.zeros(0, int)
        self._body_of_geom = model.geom_bodyid
        self._root = model.body_rootid
        self._half = np.array([o.half_extents for o in objects], float).reshape(-1, 3)
        self._offset = np.array([o.center_offset for o in objects], float).reshape(-1, 3)

    def __call__(self, data: mujoco.MjData) -> Visibility:
        n = len(self.objects)
        world_to_cam = extrinsic_cv(data, self.cam_id)
        width, height = self.width, self.height
        # Projected bounding boxes.
        bid = np.asarray(self.body_ids, int)
        body_rot = data.xmat[bid].reshape(n, 3, 3)
        centers = data.xpos[bid] + np.einsum("nij,nj->ni", body_rot, self._offset)
        corners = centers[:, None, :] + np.einsum(
            "nij,nkj->nki", body_rot, _CUBE[None] * self._half[:, None, :]
        )
        uv, z = project(corners.reshape(-1, 3), self.K, world_to_cam)
        uv, z = uv.reshape(n, 8, 2), z.reshape(n, 8)
        near = 0.1
        in_image = np.zeros(n)
        front = np.all(z > near, axis=1)
        lo, hi = uv.min(axis=1), uv.max(axis=1)
        area = np.prod(hi - lo, axis=1)
        clo, chi = np.maximum(lo, 0), np.minimum(hi, [width, height])
        inter = np.prod(np.clip(chi - clo, 0, None), axis=1)
        ok = front & (area > 0)
        in_image[ok] = inter[ok] / area[ok]
        # Unoccluded surface samples via ray casts from the camera centre.
        unocc = np.zeros(n)
        if self._local.size:
            gx = data.geom_xpos[self._geom]
            gm = data.geom_xmat[self._geom].reshape(-1, 3, 3)
            pts = gx + np.einsum("nij,nj->ni", gm, self._local)
            puv, pz = project(pts, self.K, world_to_cam)
            inside = (
                (pz > near) & (puv[:, 0] >= 0) & (puv[:, 0] < width) & (puv[:, 1] >= 0) & (puv[:, 1] < height)
            )
            idx = np.flatnonzero(inside & front[self._owner])
            if idx.size:
                cam = data.cam_xpos[self.cam_id].copy()
                vec = pts[idx] - cam
                dist_target = np.linalg.norm(vec, axis=1)
                vec /= dist_target[:, None]
                geomid = np.full(idx.size, -1, np.int32)
                dist = np.zeros(idx.size)
                mujoco.mj_multiRay(
                    self.model,
                    data,
                    cam,
                    vec.reshape(-1),
                    _RAY_GROUPS,
                    1,
                    self.exclude_body,
                    geomid,
                    dist,
                    None,
                    idx.size,
                    1e3,
                )
                hit_body = np.where(geomid >= 0, self._body_of_geom[np.maximum(geomid, 0)], -1)
                # A ray that ends on the object's own moving part (a rocker, a plunger) sees the object.
                own = (hit_body >= 0) & (
                    self._root[np.maximum(hit_body, 0)] == self._root[bid[self._owner[idx]]]
                )
                clear = (geomid < 0) | (dist >= dist_target - 1e-3)
                seen = own | clear
                tot = np.bincount(self._owner[idx], minlength=n)
                vis = np.bincount(self._owner[idx], weights=seen, minlength=n)
                unocc = np.divide(vis, tot, out=np.zeros(n), where=tot > 0)
        frac = in_image * unocc
        visible = frac >= VISIBLE_THRESHOLD
        # Target point: centre of the in-image part of the projected box (always inside the image).
        uv_norm = np.where(visible[:, None], 0.5 * (clo + chi) / np.array([width, height]), -1.0)
        return Visibility(visible, frac, in_image, unocc, uv_norm)


def surface_point_visible(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    cam_id: int,
    point,
    normal,
    geom: int,
    width: int,
    height: int,
    exclude_body: int = -1,
    min_cos: float = 0.25,
) -> bool:
    """Whether a small surface patch (``point`` with outward ``normal``, on ``geom``) is seen by the
    camera: in the image, facing it (cos >= ``min_cos``), and the first thing a ray from the camera hits."""
    point, normal = np.asarray(point, float), np.asarray(normal, float)
    cam = data.cam_xpos[cam_id].copy()
    to_cam = cam - point
    dist = float(np.linalg.norm(to_cam))
    if normal @ to_cam < min_cos * dist:
        return False
    intrinsic_matrix = intrinsics(float(model.cam_fovy[cam_id]), width, height)
    uv, z = project(point[None], intrinsic_matrix, extrinsic_cv(data, cam_id))
    if z[0] <= 0.1 or not (0 <= uv[0, 0] < width and 0 <= uv[0, 1] < height):
        return False
    geomid = np.array([-1], np.int32)
    mujoco.mj_ray(model, data, cam, -to_cam / dist, _RAY_GROUPS, 1, exclude_body, geomid)
    return int(geomid[0]) == geom
