"""A scene under construction and the regions tasks place objects in.

A task's ``layout(draft)`` places its registered objects by region: distance band, workspace angles
(90 deg = straight ahead), level, side (``left`` = angles above 90 deg) and whether the object must
be out of the head camera's home view (``hidden=True``; both sides are used, paper's release:
|theta - 90| in [38.5, 70] deg). The sampler (``sampling.py``) then adds clutter, compiles the scene
and checks the design principles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from ..sim.assets import ASSETS, categories
from ..sim.look import draw_look
from ..sim.scene import SceneBuilder
from ..sim.workspace import TABLE_TOP, WORKSPACES

# Top-down grasps and presses reach here at every angle (analysis/tasks/initial_view.py).
REACH_R = (0.34, 0.45)
# The upper band (0.60-0.80 m) where both arms reach a side-grasp pose 6 cm over it at every heading
# of the placement span (analysis/tasks/reach_band.py --level upper); its outer 5 cm are out of reach.
UPPER_REACH_R = (0.62, 0.72)
LEVEL_REACH_R = (REACH_R, UPPER_REACH_R)  # a region's default distances per level
CLUTTER_R = (0.55, 1.0)  # beyond the arms' working band
UPPER_CLUTTER_R = (0.64, 0.76)  # the upper band, its edges kept clear
# Lower-fan clutter of a two-level scene starts further out: the arms' two-level home holds the
# grippers at r 0.57 m, 0.19 m over the table, and the torso sweeps them round at that radius.
TWO_LEVEL_LOWER_CLUTTER_R = (0.66, 1.0)
# Clutter per level of a two-level scene (ID; OOD adds two below, one above).
TWO_LEVEL_CLUTTER = (5, 3)
FAN_ANGLES = (20.0, 160.0)  # the lower fan's placement span (20 deg margin at each end)
SIDE_ANGLES = {"right": (20.0, 90.0), "left": (90.0, 160.0)}
# Out of the home view candidates (paper's release: |theta - 90| in [38.5, 70] deg); each placement
# is then checked against the home camera's projection.
HIDDEN_ANGLES = {"right": (20.0, 51.5), "left": (128.5, 160.0)}


def id_clutter_pool() -> list[str]:
    """ID clutter: distractors whose family is no task category's (the paper: the ID pool excludes
    every category that some task uses, near-duplicates included)."""
    task_families = {ASSETS[c].family for c in categories("task")}
    return [c for c in categories("distractor") if ASSETS[c].family not in task_families]


class SamplingError(RuntimeError):
    """No valid placement in this draft; the sampler retries with a derived seed."""


@dataclass(frozen=True)
class Region:
    """Where an object may go. ``hidden``: True = out of the home view, False = in it, None = either;
    ``side``: 'left' / 'right' / None (any; a hidden region then picks a side at random); ``level``:
    0 the lower fan, 1 the upper band (two-level tasks); ``r`` defaults to the level's reach band."""

    r: tuple[float, float] | None = None
    angle: tuple[float, float] = FAN_ANGLES
    hidden: bool | None = None
    side: str | None = None
    level: int = 0

    def __post_init__(self):
        if self.level not in (0, 1):
            raise ValueError(f"region level must be 0 (lower fan) or 1 (upper band), got {self.level}")
        if self.r is None:
            object.__setattr__(self, "r", LEVEL_REACH_R[self.level])

    def on(self, side: str) -> Region:
        return replace(self, side=side)

    def angles(self, side: str | None) -> tuple[float, float]:
        lo, hi = self.angle
        if self.hidden and side is not None:
            h = HIDDEN_ANGLES[side]
            lo, hi = max(lo, h[0]), min(hi, h[1])
        elif side is not None:
            s = SIDE_ANGLES[side]
            lo, hi = max(lo, s[0]), min(hi, s[1])
        if lo > hi:
            raise ValueError(f"region {self} has no angles on the {side} side")
        return lo, hi


REACH = Region()  # anywhere in the arms' band
HIDDEN = Region(hidden=True)  # in the arms' band, out of the home view, random side
CLUTTER = Region(r=CLUTTER_R)
# A destination on the upper band: its 20 cm depth leaves one distance (0.70 m) for a ~20 cm plate or
# basket, anywhere in the placement span. The expert sets objects down there from the side
# (``skills.place_on_upper``): no top-down pose reaches the band.
ON_UPPER_BAND = Region(r=(0.70, 0.70), level=1)


def draw_level(draft: SceneDraft, name: str, upper_share: float) -> bool:
    """Whether the destination ``name`` stands on the upper band this episode (with probability
    ``upper_share``, else on the lower fan); recorded as ``params['<name>_level']`` (0 / 1)."""
    upper = bool(draft.rng.random() < upper_share)
    draft.params[f"{name}_level"] = int(upper)
    return upper


@lru_cache(maxsize=1)
def _home_camera() -> tuple[np.ndarray, np.ndarray]:
    """Intrinsics and world-to-camera of the head camera at home (robot only)."""
    import mujoco

    from ..sim import embodiment
    from ..sim.camera import extrinsic_cv, intrinsics
    from ..sim.scene import HEAD_HEIGHT, HEAD_WIDTH

    model, _ = SceneBuilder().compile()
    data = mujoco.MjData(model)
    data.qpos[model.joint(embodiment.TORSO_YAW_JOINT).qposadr[0]] = embodiment.HOME_TORSO_YAW
    data.qpos[model.joint(embodiment.HEAD_PITCH_JOINT).qposadr[0]] = embodiment.HOME_HEAD_PITCH
    mujoco.mj_forward(model, data)
    cam = model.camera(embodiment.HEAD_CAMERA).id
    return intrinsics(float(model.cam_fovy[cam]), HEAD_WIDTH, HEAD_HEIGHT), extrinsic_cv(data, cam)


def in_home_view(xy, radius: float, heights=(0.005, 0.08), top_z: float = TABLE_TOP) -> bool:
    """Whether any point of the disc (``xy``, ``radius``) at the given heights above a tabletop at
    ``top_z`` projects into the home image (occlusion is left to the sampler's visibility check)."""
    from ..sim.camera import project
    from ..sim.scene import HEAD_HEIGHT, HEAD_WIDTH

    intrinsic_matrix, world_to_cam = _home_camera()
    ring = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    pts = [
        [xy[0] + radius * math.cos(a), xy[1] + radius * math.sin(a), top_z + h] for a in ring for h in heights
    ]
    pts += [[xy[0], xy[1], top_z + h] for h in heights]
    uv, z = project(np.asarray(pts), intrinsic_matrix, world_to_cam)
    inside = (
        (z > 0) & (uv[:, 0] >= 0) & (uv[:, 0] <= HEAD_WIDTH) & (uv[:, 1] >= 0) & (uv[:, 1] <= HEAD_HEIGHT)
    )
    return bool(inside.any())


class SceneDraft:
    """Non-overlapping placement on the task's workspace (per level), registered object labels,
    episode parameters."""

    def __init__(self, split: str, rng: np.random.Generator, workspace: str = "fan"):
        self.split, self.rng = split, rng
        # The look comes from a stream of its own: appearance never moves an object.
        self.look = draw_look(split, rng.spawn(1)[0])
        self.builder = SceneBuilder(workspace=WORKSPACES[workspace](), look=self.look)
        self.workspace = self.builder.workspace
        self.discs: list[tuple[np.ndarray, float, int]] = []  # (xy, radius, level) kept clear
        self.labels: list[str] = []
        self.params: dict = {}
        self.hidden: list[str] = []  # objects placed out of the home view (checked after compiling)
        self.reach: dict[str, tuple[str, ...]] = {}  # object -> arms allowed to touch it
        self.placements: list[dict] = []  # (name, role, r, angle) of every registered object
        self.clutter_excluded: set[str] = set()  # asset families the clutter must not use
        self.reading_shift = 0  # counterfactual scenes: ``draw_reading`` moves the drawn reading on by it
        self.reading_drawn = False

        if self.workspace.two_level:  # the upper band's column stands on the lower fan
            a = math.radians(self.workspace.level(1).center_deg)
            column = self.workspace.column_r * np.array([math.cos(a), math.sin(a)])
            self.discs.append((column, self.workspace.column_half * math.sqrt(2), 0))

    def is_free(self, xy, radius: float, margin: float, level: int = 0) -> bool:
        return all(
            np.linalg.norm(np.asarray(xy) - p) >= radius + r + margin
            for p, r, lv in self.discs
            if lv == level
        )

    def keep_clear(self, xy, radius: float, level: int = 0) -> None:
        """Keep the disc (``xy``, ``radius``) on ``level`` free of later placements."""
        self.discs.append((np.asarray(xy, float), radius, level))

    def reserve(self, distance: float, angle_deg: float, radius: float, level: int = 0) -> None:
        """Keep a disc empty (e.g. where an object will be placed later)."""
        try:
            xy = self.workspace.place(distance, angle_deg, level)[:2]
        except ValueError as exc:  # off the fan: this draft cannot hold the layout
            raise SamplingError(str(exc)) from exc
        self.keep_clear(xy, radius, level)

    def draw_reading(self, choices: tuple) -> object:
        """Draw the hidden information (an IA task's reading) from ``choices``. ``reading_shift`` k > 0
        gives the scene's counterfactual: the same draws, the reading k choices on, everything else
        as it is (recorded as ``params['reading_shift']``)."""
        drawn = int(self.rng.integers(0, len(choices)))
        self.reading_drawn = True
        if self.reading_shift:
            self.params["reading_shift"] = self.reading_shift
        return choices[(drawn + self.reading_shift) % len(choices)]

    def side(self) -> str:
        return "left" if self.rng.integers(0, 2) else "right"

    def random_yaw(self) -> float:
        return float(self.rng.uniform(-np.pi, np.pi))

    def place(
        self,
        category: str,
        name: str,
        label: str,
        region: Region = REACH,
        *,
        r=None,
        angle=None,
        yaw: float | str | None = None,
        arms: tuple[str, ...] = (),
        margin: float = 0.04,
        register: bool = True,
        static: bool = False,
        tries: int = 200,
        yaw_jitter: float = 0.25,
        half_depth: float | None = None,
        **params,
    ):
        """Sample a free spot in ``region`` (or the explicit ``r`` / ``angle``, a value or a range) and
        add the object. ``yaw``: radians, ``'random'``, or None (body +x points radially outward, give or
        take ``yaw_jitter`` rad). ``arms``: the arms that may touch it (checked reachable by the sampler).
        ``half_depth``: how far the object reaches along the radius either side of its centre, for
        the upper band's fit (default: its footprint radius; an oblong object placed with a known
        yaw reaches less far across the band than its footprint circle).
        Returns (ObjectInfo, distance, angle_deg)."""
        foot = ASSETS[category].footprint
        if half_depth is not None and not 0 < half_depth <= foot:
            raise ValueError(f"{name}: half_depth {half_depth} must be in (0, footprint {foot}]")
        depth = foot if half_depth is None else half_depth
        side = region.side if region.side is not None or not region.hidden else self.side()
        r = region.r if r is None else r
        angle = region.angles(side) if angle is None else angle
        level = self.workspace.level(region.level)
        for _ in range(tries):
            rr = float(self.rng.uniform(*r)) if np.ndim(r) else float(r)
            aa = float(self.rng.uniform(*angle)) if np.ndim(angle) else float(angle)
            try:
                xy = self.workspace.place(rr, aa, region.level)[:2]
            except ValueError as exc:  # an explicit spot off the fan
                raise SamplingError(f"{name}: {exc}") from exc
            # the upper band is 20 cm deep: the whole footprint must stand on it
            if region.level > 0 and not level.inner_radius + depth <= rr <= level.outer_radius - depth:
                continue
            if not self.is_free(xy, foot, margin, region.level):
                continue
            if region.hidden is not None and in_home_view(xy, foot, top_z=level.top_z) == region.hidden:
                continue
            break
        else:
            raise SamplingError(
                f"no free spot for {name} ({category}) in r={r}, angle={angle}, hidden={region.hidden}"
            )
        if yaw == "random":
            yaw = self.random_yaw()
        elif yaw is None:
            yaw = math.radians(aa) + float(self.rng.uniform(-yaw_jitter, yaw_jitter))
        info = self.builder.add_object(
            category,
            name,
            rr,
            aa,
            level=region.level,
            yaw=yaw,
            rng=self.rng,
            register=register,
            static=static or ASSETS[category].static,
            **params,
        )
        self.keep_clear(xy, foot, region.level)
        if register:
            self.labels.append(label)
            placement = {
                "name": name,
                "category": category,
                "r": rr,
                "angle": aa,
                "hidden": bool(region.hidden),
            }
            if self.workspace.two_level:
                placement["level"] = region.level
            self.placements.append(placement)
            if region.hidden:
                self.hidden.append(name)
            if arms:
                self.reach[name] = tuple(arms)
        return info, rr, aa

    def add_clutter(self) -> int:
        """Static distractors beyond the arms' band (two-level: on both levels); returns how many
        fitted."""
        ood = self.split == "ood"
        present = {ASSETS[o.category].family for o in self.builder.info.objects} | self.clutter_excluded
        pool = [c for c in (categories() if ood else id_clutter_pool()) if ASSETS[c].family not in present]
        if self.workspace.two_level:
            lower, upper = TWO_LEVEL_CLUTTER
            plan = [
                (Region(r=TWO_LEVEL_LOWER_CLUTTER_R), lower + 2 * ood),
                (Region(r=UPPER_CLUTTER_R, level=1), upper + ood),
            ]
        else:
            plan = [(CLUTTER, int(self.rng.integers(9, 14) if ood else self.rng.integers(4, 8)))]
        placed = k = 0
        for region, n in plan:
            for _ in range(n):
                if not pool:
                    break
                cat = pool[int(self.rng.integers(0, len(pool)))]
                try:
                    self.place(
                        cat,
                        f"clutter_{k}_{cat}",
                        cat,
                        region,
                        margin=0.02 if region.level == 0 else 0.06,  # upper: room for a side entry
                        register=False,
                        static=True,
                        tries=40,
                    )
                except SamplingError:
                    continue
                finally:
                    k += 1
                placed += 1
                if ood:  # no near-duplicates in one scene
                    fam = ASSETS[cat].family
                    pool = [c for c in pool if ASSETS[c].family != fam]
        return placed
