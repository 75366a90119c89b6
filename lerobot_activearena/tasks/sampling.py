"""Scene sampling from (task, seed, split) with the design-principle checks and deterministic retries.

ID: task objects plus a few static distractors from the distractor pool (no category that any task
uses), in one of a few fixed looks (table, floor and wall materials; one light). OOD: held-out
materials and lighting (``sim/look``) and denser clutter from the full pool, excluding families
already in the scene, so other tasks' objects appear as distractors. The look is drawn from a
stream of its own, so it never moves an object.
"""

from __future__ import annotations

import zlib

import mujoco
import numpy as np

from ..expert.kinematics import side_reachable, top_down_reachable
from ..sim import embodiment
from ..sim.blas_kernels import use_pinned_kernels
from ..sim.head_camera import head_visibility_checker, search_views
from ..sim.simulator import ActiveArenaSim
from .base import SPLITS, Task, TaskScene
from .draft import SamplingError, SceneDraft
from .success import SuccessMonitor

MAX_ATTEMPTS = 25


def derived_rng(task: str, seed: int, split: str, attempt: int) -> np.random.Generator:
    key = [int(seed), int(attempt), SPLITS.index(split), zlib.crc32(task.encode())]
    return np.random.default_rng(np.random.SeedSequence(key))


def sector_visibility(model: mujoco.MjModel, info, views=None) -> np.ndarray:
    """(n_views, n_objects) visibility of the registered objects from each (torso yaw, head pitch)
    (default: the workspace's search views; row 0 is home) with the robot at home (no physics step:
    spawn poses)."""
    views = search_views(info.workspace) if views is None else views
    data = mujoco.MjData(model)
    checker = head_visibility_checker(model, info.objects)
    qy = model.joint(embodiment.TORSO_YAW_JOINT).qposadr[0]
    qp = model.joint(embodiment.HEAD_PITCH_JOINT).qposadr[0]
    out = []
    for yaw, pitch in views:
        data.qpos[:] = model.qpos0
        data.qpos[qy], data.qpos[qp] = yaw, pitch
        mujoco.mj_forward(model, data)
        out.append(checker(data).visible)
    return np.array(out)


def principle_violations(task: Task, scene: TaskScene) -> list[str]:
    """The checkable design principles (paper App. "Task Design Principles"): (1) the initial view
    does not show every task-relevant object; (2) each of them is visible from some search view and
    every object the arms must touch is reachable by an allowed arm; (3) with several, no single
    view shows them all (evidence must be remembered). Objects placed out of the home view must
    not be visible there, nor any information face (a back patch, a date label)."""
    targets = scene.search_targets
    vis_all = sector_visibility(scene.model, scene.info)
    vis = vis_all[:, targets]
    problems = []
    # With the deciding information hidden by construction (a back-face colour), (1) and (3) hold
    # through it: it is unseen at reset and must be remembered once the face is turned away again.
    hidden_info = task.information_hidden_at_start(scene)
    if task.information_faces(scene) and not hidden_info:
        problems.append("an information face is visible at home")
    if vis[0].all() and not hidden_info:
        problems.append("initial view already shows every task-relevant object")
    missing = [scene.objects[t] for t, seen in zip(targets, vis.any(axis=0), strict=True) if not seen]
    if missing:
        problems.append(f"never visible from any search view: {missing}")
    if len(targets) > 1 and vis.all(axis=1).any() and not hidden_info:
        problems.append("one search view shows every task-relevant object")
    shown = [n for n in scene.hidden if vis_all[0][scene.objects.index(n)]]
    if shown:
        problems.append(f"placed out of the home view but visible there: {shown}")
    data = mujoco.MjData(scene.model)
    mujoco.mj_kinematics(scene.model, data)
    ws = scene.info.workspace
    for name, arms in scene.reach.items():
        obj = scene.obj(name)
        body = data.body(obj.body)
        center = body.xpos + body.xmat.reshape(3, 3) @ np.asarray(obj.center_offset)
        if ws.two_level and center[2] > ws.level(1).top_z:  # on the upper band: the side grasp
            ok = any(side_reachable(center, side, height=0.0) for side in arms)
        else:
            ok = any(top_down_reachable(center + [0, 0, obj.half_extents[2]], side) for side in arms)
        if not ok:
            problems.append(f"{name} is out of reach of the {'/'.join(arms)} arm")
    return problems


def goal_holds_at_reset(task: Task, scene: TaskScene) -> list[str]:
    """The task's success checks that already hold in the spawned scene (all of them: reject)."""
    sim = ActiveArenaSim(scene.model, scene.info)
    try:
        checks = task.evaluate(sim, scene, SuccessMonitor(task, sim, scene))
    finally:
        sim.close()
    return ["the goal already holds at reset"] if checks and all(checks.values()) else []


def sample_scene(task: Task, seed: int, split: str = "id", reading_shift: int = 0) -> TaskScene:
    """Sample the scene of (task, seed, split); retries with derived seeds until the design
    principles hold (deterministic: the same inputs give the same scene). ``reading_shift`` k > 0:
    the scene's counterfactual, its hidden reading k choices on (``SceneDraft.draw_reading``)."""
    if split not in SPLITS:
        raise ValueError(f"split must be one of {SPLITS}, got {split!r}")
    if reading_shift < 0:
        raise ValueError(f"reading_shift is a number of choices >= 0, got {reading_shift}")
    use_pinned_kernels()  # the same BLAS kernels on every x86-64 CPU (sim/blas_kernels.py)
    reasons = []
    for attempt in range(MAX_ATTEMPTS):
        draft = SceneDraft(split, derived_rng(task.name, seed, split, attempt), task.workspace)
        draft.reading_shift = reading_shift
        try:
            task.layout(draft)
        except SamplingError as exc:
            reasons.append(str(exc))
            continue
        if reading_shift and not draft.reading_drawn:
            raise ValueError(
                f"{task.name} draws no hidden reading (SceneDraft.draw_reading), so it has no counterfactual "
                "scenes: build it with --reading-variants 1"
            )
        draft.params["n_clutter"] = draft.add_clutter()
        model, info = draft.builder.compile()
        scene = TaskScene(
            task.name,
            seed,
            split,
            attempt,
            model,
            info,
            [o.name for o in info.objects],
            list(draft.labels),
            dict(draft.params),
            task.instruction_for(draft.params),
            hidden=list(draft.hidden),
            reach=dict(draft.reach),
        )
        scene.params["placements"] = draft.placements
        scene.search_targets = task.search_targets(scene)
        problems = principle_violations(task, scene) or goal_holds_at_reset(task, scene)
        if not problems:
            scene.params["rejected_attempts"] = reasons
            return scene
        reasons.append("; ".join(problems))
    raise SamplingError(
        f"{task.name} seed {seed} ({split}): no valid scene in {MAX_ATTEMPTS} attempts: {reasons[-3:]}"
    )
