"""Assemble a scene with MjSpec: physics options, the room and its light, robot, workspace and objects."""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

from . import embodiment
from .action import CONTROL_HZ
from .assets import ObjectInfo, build_asset
from .look import CEILING, DEFAULT_LOOK, Look
from .look.materials import add_surface_material
from .look.room import add_room, add_sky
from .look.tabletop import add_tabletop_visual
from .workspace import COLLISION_ONLY_GROUP, Workspace, add_workspace, fan_workspace

SUBSTEPS = 32  # physics steps per control step: dt = 1/480 s
HEAD_WIDTH, HEAD_HEIGHT = 512, 384
HEAD_SIZE = (HEAD_HEIGHT, HEAD_WIDTH)  # the paper's head image (height, width)
WRIST_WIDTH, WRIST_HEIGHT = 320, 240
WRIST_FOVY = 37.0


@dataclass
class SceneInfo:
    """Everything the simulator needs to know about a compiled scene besides the MjModel."""

    workspace: Workspace
    robot: embodiment.RobotSpecInfo
    objects: list[ObjectInfo] = field(default_factory=list)  # registered objects (visibility, masks)
    wrist_cameras: bool = False
    clutter: list[ObjectInfo] = field(default_factory=list)  # unregistered static distractors


class SceneBuilder:
    """Builds one scene. Add objects, then ``compile()`` to an ``MjModel``."""

    def __init__(
        self,
        workspace: Workspace | None = None,
        wrist_cameras: bool = False,
        shadows: bool = False,
        look: Look | None = None,
    ):
        """``look``: the room's materials and light (appearance only; ``sim/look``). ``shadows``:
        the key light casts shadows (costs render time on a CPU, see docs/sim.md)."""
        self.workspace = workspace or fan_workspace()
        self.shadows = shadows
        self.look = look or DEFAULT_LOOK
        self.spec = mujoco.MjSpec()
        self.spec.modelname = "activearena"
        self._set_options()
        self._add_environment()
        add_workspace(self.spec, self.workspace)
        self._dress_tabletop()
        robot = embodiment.add_robot(self.spec)
        self.info = SceneInfo(self.workspace, robot, wrist_cameras=wrist_cameras)
        for cam in embodiment.WRIST_CAMERAS.values():
            if wrist_cameras:
                self.spec.camera(cam).fovy = WRIST_FOVY  # paper's wrist preset: 320x240, 37 deg
            else:
                self.spec.delete(self.spec.camera(cam))

    def _set_options(self) -> None:
        opt = self.spec.option
        opt.timestep = 1.0 / (CONTROL_HZ * SUBSTEPS)
        opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
        opt.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
        opt.impratio = 10.0
        opt.noslip_iterations = 3
        opt.iterations = 50
        # Resting objects sleep until touched: ~5x faster physics for cluttered tables.
        opt.enableflags |= int(mujoco.mjtEnableBit.mjENBL_SLEEP)
        vis = self.spec.visual
        vis.global_.offwidth, vis.global_.offheight = HEAD_WIDTH, HEAD_HEIGHT
        vis.quality.offsamples = 0  # no multisampling: fast CPU rendering
        vis.quality.shadowsize = 1024
        vis.quality.numslices = vis.quality.numstacks = 16  # light tessellation of round primitives
        self.spec.stat.extent = 2.0
        self.spec.stat.center = (0.0, 0.4, 0.9)
        vis.map.znear = 0.1 / self.spec.stat.extent  # 0.1 m
        vis.map.zfar = 100.0 / self.spec.stat.extent  # 100 m
        amb = self.look.lighting.ambient
        vis.headlight.ambient = (amb, amb, amb)
        vis.headlight.diffuse = (0.05, 0.05, 0.05)  # a little fill from the camera
        vis.headlight.specular = (0.0, 0.0, 0.0)

    def _add_environment(self) -> None:
        """Floor (the collision plane, textured), walls, ceiling, sky and the key light."""
        spec, look = self.spec, self.look
        add_surface_material(spec, "floor", look.floor)
        add_surface_material(spec, "wall", look.wall)
        add_surface_material(spec, "ceiling", CEILING)
        floor = spec.worldbody.add_geom()
        floor.name = "floor"
        floor.type = mujoco.mjtGeom.mjGEOM_PLANE
        floor.size = (6, 6, 0.1)
        floor.material = "floor"
        floor.contype = floor.conaffinity = 1
        add_room(spec, "wall", "ceiling")
        add_sky(spec)
        light = spec.worldbody.add_light()
        light.name = "key_light"
        light.type = mujoco.mjtLightType.mjLIGHT_DIRECTIONAL
        light.pos = (0.0, 0.0, 2.6)
        light.dir = look.lighting.direction
        light.diffuse = look.lighting.diffuse
        light.specular = (0.05, 0.05, 0.05)
        light.castshadow = self.shadows

    def _dress_tabletop(self) -> None:
        """The collision patches hide; a textured slab of the same outline shows each level."""
        add_surface_material(self.spec, "table", self.look.table, uniform=False)
        for g in self.spec.geoms:
            if g.material == "tabletop":
                g.group = COLLISION_ONLY_GROUP
        for idx, lv in enumerate(self.workspace.levels):
            add_tabletop_visual(self.spec, self.spec.body(f"fan_level_{idx}"), lv, f"fan_top_{idx}", "table")

    def add_object(
        self,
        kind: str,
        name: str,
        distance: float,
        angle_deg: float,
        level: int = 0,
        yaw: float = 0.0,
        rng: np.random.Generator | None = None,
        register: bool = True,
        static: bool = False,
        **params,
    ) -> ObjectInfo:
        """Place an object on the workspace at robot-centric cylindrical coordinates: ``distance``
        (radius from the robot base, m), ``angle_deg`` and ``level``; ``params`` go to the builder."""
        pos = self.workspace.place(distance, angle_deg, level)
        return self.add_object_at(
            kind,
            name,
            pos + np.array([0, 0, 0.0005]),
            yaw,
            rng=rng,
            register=register,
            static=static,
            **params,
        )

    def add_object_at(
        self,
        kind: str,
        name: str,
        pos,
        yaw: float = 0.0,
        rng: np.random.Generator | None = None,
        register: bool = True,
        static: bool = False,
        **params,
    ) -> ObjectInfo:
        """Place an object at a world position (its bottom centre). ``register=False`` adds it as
        clutter (no visibility/annotation bookkeeping); ``static=True`` fixes it to the world."""
        if any(o.name == name for o in self.info.objects + self.info.clutter):
            raise ValueError(f"an object named {name!r} is already in the scene; names must be unique")
        obj = build_asset(self.spec, kind, name, pos, yaw, rng=rng, **params)
        if static:
            body = self.spec.body(obj.body)
            for j in list(body.joints):
                if j.type == mujoco.mjtJoint.mjJNT_FREE:
                    self.spec.delete(j)
        (self.info.objects if register else self.info.clutter).append(obj)
        return obj

    def compile(self) -> tuple[mujoco.MjModel, SceneInfo]:
        model = self.spec.compile()
        return model, self.info


def reference_scene(seed: int = 0, n_objects: int = 25, target: str | None = None) -> SceneBuilder:
    """Robot + fan table + ``n_objects`` primitives scattered over the fan (benchmarks, demos).
    With ``target``, a 0.3 kg red can of that name stands in the right arm's reach first."""
    rng = np.random.default_rng(seed)
    builder = SceneBuilder()
    kinds = ["can", "block", "ball", "bottle"]
    placed: list[np.ndarray] = []
    reserved: list[np.ndarray] = []
    if target:
        builder.add_object("can", target, 0.45, 60.0, mass=0.3, rgba=(0.8, 0.08, 0.08, 1.0))
        reserved.append(builder.workspace.place(0.45, 60.0)[:2])
    lo, hi = builder.workspace.placement_span_deg(0)
    tries = 0
    while len(placed) < n_objects:
        tries += 1
        if tries > 5000:
            raise RuntimeError(f"could not place {n_objects} objects without overlap")
        r = rng.uniform(0.38, 1.0)
        a = rng.uniform(lo, hi)
        xy = builder.workspace.place(r, a)[:2]
        if any(np.linalg.norm(xy - p) < 0.11 for p in placed) or any(
            np.linalg.norm(xy - p) < 0.2 for p in reserved
        ):
            continue
        kind = kinds[len(placed) % len(kinds)]
        rgba = (*rng.uniform(0.1, 0.95, 3), 1.0)
        builder.add_object(kind, f"{kind}_{len(placed)}", r, a, yaw=rng.uniform(-np.pi, np.pi), rgba=rgba)
        placed.append(xy)
    return builder
