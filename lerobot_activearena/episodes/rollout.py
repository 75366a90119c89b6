"""The scripted expert's episodes: ``ExpertDriver`` steps a task's expert script (also behind the
env's expert channel) and ``run_expert_episode`` plays one (task, seed, split) on the episode
stepper, returning actions, per-frame annotations, sidecar, success and physics health. The single
entry point for videos, datasets and expert evaluation. Demonstrations must also keep every contact
shallower than ``PENETRATION_LIMIT``.
"""

from __future__ import annotations

import logging
import math
import time
import zlib
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..annotations.writer import AnnotationWriter
from ..expert.context import MAX_FACE_JITTER, MAX_GRASP_MISS, PRESS_ARMS, ExpertContext, ExpertError
from ..expert.kinematics import shared_kinematics
from ..sim.action import GRIPPER_INDICES, TORSO_YAW
from ..sim.health import PENETRATION_LIMIT
from ..sim.perception import PerceptionMemory
from ..sim.scene import HEAD_SIZE
from ..sim.simulator import ActiveArenaSim
from ..tasks.base import Task, TaskScene
from ..tasks.registry import get_task
from ..tasks.sampling import sample_scene
from .episode import Episode

log = logging.getLogger(__name__)


@dataclass
class EpisodeResult:
    task: str
    seed: int
    split: str
    success: bool
    failure: str | None
    actions: np.ndarray  # (T, 18) commanded joint targets
    states: np.ndarray  # (T, 18) observed joint state at each frame
    frames: list[dict]  # per-frame annotations (paper schema)
    sidecar: dict
    health: dict = field(default_factory=dict)
    seconds: float = 0.0

    @property
    def length(self) -> int:
        return len(self.frames)


def make_sidecar(
    task,
    scene: TaskScene,
    writer: AnnotationWriter,
    perception: PerceptionMemory,
    ctx: ExpertContext,
    success: bool,
    failure: str | None,
) -> dict:
    return {
        "task": task.name,
        "category": task.category,
        "instruction": scene.instruction,
        "seed": scene.seed,
        "split": scene.split,
        "scene_attempt": scene.attempt,
        "objects": [
            {"index": i, "key": n, "name": lbl, "category": scene.info.objects[i].category}
            for i, (n, lbl) in enumerate(zip(scene.objects, scene.labels, strict=True))
        ],
        "subtasks": [
            {"id": s.id, "name": s.name, "text": s.text, "instruction_idx": s.instruction_idx}
            for s in task.subtasks
        ],
        "search_targets": list(scene.search_targets),
        # the expert's search sectors: lower at the home pitch, then (two-level) pitched up
        "search_views": [
            {"torso_yaw": yaw, "head_pitch": pitch, "heading_deg": round(90.0 + math.degrees(yaw), 2)}
            for yaw, pitch in ctx.views
        ],
        "params": {k: v for k, v in scene.params.items() if k not in ("rejected_attempts", "placements")},
        "placements": scene.params.get("placements", []),
        "transitions": writer.transitions,
        "final_discovered": {scene.objects[i]: bool(d) for i, d in enumerate(perception.discovered)},
        "expert_notes": ctx.notes,
        "success": success,
        "failure": failure,
    }


@dataclass(frozen=True)
class DemoVariation:
    """How a dataset's demonstrations differ from the benchmark's expert (the defaults: they do not).
    ``search_overshoot``: ``ExpertContext``'s recovery demonstrations; ``action_noise``: ``ActionNoise``'s
    sigma in rad; ``face_jitter``: ``ExpertContext``'s off-centre demonstrations (rad);
    ``decision_period``: ``ExpertContext``'s chunk-aligned search (1: every frame);
    ``press_arm``: ``ExpertContext``'s one arm for the count-and-press tasks' press (None: the arm on
    the button's half of the fan); ``reading_variants`` N > 1: counterfactual readings, seed s plays
    scene s // N with its hidden reading shifted by s % N (``sample_scene``), so each scene is
    demonstrated with N readings and N decisions; ``turn_error``: ``TurnError``'s largest angle in rad;
    ``turn_error_subtask`` K >= 2: ``TurnError`` also turns the first frames of subtask K (0: none);
    ``grasp_miss``: ``ExpertContext``'s grasp-retry demonstrations (m)."""

    search_overshoot: float = 0.0
    action_noise: float = 0.0
    decision_period: int = 1
    press_arm: str | None = None
    face_jitter: float = 0.0
    reading_variants: int = 1
    turn_error: float = 0.0
    turn_error_subtask: int = 0
    grasp_miss: float = 0.0

    def __post_init__(self):
        if not 0.0 <= self.search_overshoot <= 1.0:
            raise ValueError(f"--search-overshoot is a probability in [0, 1], got {self.search_overshoot}")
        if not 0.0 <= self.action_noise <= MAX_ACTION_NOISE:
            raise ValueError(
                f"--action-noise is a joint standard deviation in [0, {MAX_ACTION_NOISE}] rad, got "
                f"{self.action_noise}"
            )
        if not 0.0 <= self.face_jitter <= MAX_FACE_JITTER:
            raise ValueError(
                f"--face-jitter is an angle in [0, {MAX_FACE_JITTER}] rad, got {self.face_jitter}"
            )
        if not 0.0 <= self.turn_error <= MAX_TURN_ERROR:
            raise ValueError(f"--turn-error is an angle in [0, {MAX_TURN_ERROR}] rad, got {self.turn_error}")
        if self.turn_error_subtask and (self.turn_error_subtask < 2 or not self.turn_error):
            raise ValueError(
                "--turn-error-subtask K turns the torso off at the start of subtask K >= 2 (subtask 1 starts the "
                f"episode, which --turn-error turns) and needs --turn-error > 0, got K={self.turn_error_subtask} "
                f"with --turn-error {self.turn_error}"
            )
        if not 0.0 <= self.grasp_miss <= MAX_GRASP_MISS:
            raise ValueError(f"--grasp-miss is a distance in [0, {MAX_GRASP_MISS}] m, got {self.grasp_miss}")
        if not isinstance(self.decision_period, int) or self.decision_period < 1:
            raise ValueError(
                f"--decision-period is a number of frames >= 1 (1: the benchmark's expert), got "
                f"{self.decision_period!r}"
            )
        if not isinstance(self.reading_variants, int) or self.reading_variants < 1:
            raise ValueError(
                f"--reading-variants is a number of readings per scene >= 1 (1: the benchmark's scenes), got "
                f"{self.reading_variants!r}"
            )
        if self.press_arm not in PRESS_ARMS:
            raise ValueError(
                f"--press-arm is 'left' or 'right' (unset: the arm on the button's half), got {self.press_arm!r}"
            )


MAX_ACTION_NOISE = 0.1  # rad: beyond it the expert's strokes fail more often than they succeed


class ActionNoise:
    """Perturbed demonstrations for datasets (DART, Laskey et al. 2017): a smooth joint offset, an
    Ornstein-Uhlenbeck process with standard deviation ``sigma`` rad and correlation time
    ``tau_steps`` control steps, added to the arm and view joints of the action the simulator
    executes (grippers untouched). The dataset records the expert's own action, so at each perturbed
    state it shows the command that leads back onto the expert's path. Inside a contact stroke
    (``ExpertContext.precise``: a press) the offset halves every step, so the stroke lands where the
    expert aims it. Drawn from its own stream, seeded by the scene seed: deterministic, and the
    scene's sampling is not touched."""

    def __init__(self, sigma: float, seed: int, task: str, tau_steps: float = 5.0):
        if not 0.0 < sigma <= MAX_ACTION_NOISE:
            raise ValueError(
                f"action_noise is a joint standard deviation in (0, {MAX_ACTION_NOISE}] rad, got {sigma}"
            )
        self.rng = np.random.default_rng([int(seed), zlib.crc32(f"action_noise/{task}".encode())])
        self.decay = math.exp(-1.0 / tau_steps)
        self.scale = sigma * math.sqrt(1.0 - self.decay**2)  # keeps the stationary deviation at sigma
        self.mask = np.ones(18)
        self.mask[list(GRIPPER_INDICES)] = 0.0
        self.offset = np.zeros(18)  # the episode starts at home, unperturbed

    def __call__(self, action: np.ndarray, precise: bool = False) -> np.ndarray:
        step = self.rng.normal(0.0, 1.0, 18)  # drawn every step: the stream does not depend on strokes
        if precise:
            self.offset = 0.5 * self.offset
        else:
            self.offset = self.decay * self.offset + self.scale * step * self.mask
        return np.asarray(action, float) + self.offset


MAX_TURN_ERROR = 0.4  # rad: about the largest heading error of a small policy's first chunk
TURN_ERROR_STEPS = 16  # the first chunk of a policy that plays 16 actions a decision


class TurnError:
    """Turn-recovery demonstrations: during an episode's first ``steps`` frames the torso yaw the
    simulator executes is off the expert's command by one uniform angle in +/- ``angle`` rad, the
    heading a policy's first chunk (decided from the home view, nothing in memory) lands at; from
    frame ``steps`` on the expert's own commands run. The dataset records the expert's commands, so
    the frame where the error ends shows the torso and the view off the path with the command that
    turns back, which the benchmark's expert (always on its heading by then) never shows. Drawn from
    its own stream, seeded by the scene seed: deterministic, and the scene's sampling is not touched.
    ``subtask`` K: the first ``steps`` frames of subtask K are turned off too, by a second draw (the
    place's turn of an inspect-and-place task, decided from what the memory holds)."""

    def __init__(self, angle: float, seed: int, task: str, steps: int = TURN_ERROR_STEPS, subtask: int = 0):
        if not 0.0 < angle <= MAX_TURN_ERROR:
            raise ValueError(f"turn_error is an angle in (0, {MAX_TURN_ERROR}] rad, got {angle}")
        rng = np.random.default_rng([int(seed), zlib.crc32(f"turn_error/{task}".encode())])
        self.offset, self.steps, self.t = float(rng.uniform(-angle, angle)), steps, 0
        self.subtask, self.subtask_offset = subtask, float(rng.uniform(-angle, angle))
        self.subtask_start: int | None = None

    def __call__(self, action: np.ndarray, subtask: int = 0) -> np.ndarray:
        out = np.array(action, dtype=float)
        if self.subtask and subtask == self.subtask and self.subtask_start is None:
            self.subtask_start = self.t
        if self.t < self.steps:
            out[TORSO_YAW] += self.offset
        elif self.subtask_start is not None and self.t - self.subtask_start < self.steps:
            out[TORSO_YAW] += self.subtask_offset
        self.t += 1
        return out


class ExpertDriver:
    """Steps a task's expert script. Call ``next_action()`` before each simulator step and
    ``observed()`` after the episode has observed the new state. An expert that gives up
    (``ExpertError``: object never found, grasp lost) ends its script: ``failure`` says why and
    ``next_action()`` returns None from then on, as it does when the script is finished.
    ``contain_errors`` (the env's expert channel): any other exception from the script is logged
    with its traceback and fails the episode instead of the whole evaluation run."""

    def __init__(
        self,
        task: Task,
        scene: TaskScene,
        sim: ActiveArenaSim,
        perception: PerceptionMemory,
        contain_errors: bool = False,
        search_overshoot: float = 0.0,
        decision_period: int = 1,
        press_arm: str | None = None,
        face_jitter: float = 0.0,
        grasp_miss: float = 0.0,
    ):
        ik, gaze = shared_kinematics()
        self.task = task
        self.writer = AnnotationWriter(sim, perception)
        rng = None
        if search_overshoot > 0.0:  # its own stream: the scene's sampling is not touched
            rng = np.random.default_rng([int(scene.seed), zlib.crc32(f"overshoot/{task.name}".encode())])
        face_rng = None
        if face_jitter > 0.0:
            face_rng = np.random.default_rng(
                [int(scene.seed), zlib.crc32(f"face_jitter/{task.name}".encode())]
            )
        self.ctx = ExpertContext(
            sim,
            scene.objects,
            perception,
            ik,
            gaze,
            n_subtasks=len(task.subtasks),
            search_overshoot=search_overshoot,
            rng=rng,
            decision_period=decision_period,
            press_arm=press_arm,
            face_jitter=face_jitter,
            face_rng=face_rng,
            grasp_miss=grasp_miss,
            miss_rng=np.random.default_rng([int(scene.seed), zlib.crc32(f"grasp_miss/{task.name}".encode())])
            if grasp_miss > 0.0
            else None,
        )
        self._script = task.expert(self.ctx, scene)
        self.finished = False
        self.failure: str | None = None
        self.contain_errors = contain_errors
        self.ctx.update_memory()

    def next_action(self) -> np.ndarray | None:
        if self.finished:
            return None
        try:
            return next(self._script)
        except StopIteration:
            pass
        except ExpertError as exc:
            self.failure = f"expert: {exc}"
        except Exception as exc:
            if not self.contain_errors:
                raise
            log.exception("the %s expert crashed; its episode fails", self.task.name)
            self.failure = f"expert crashed: {type(exc).__name__}: {exc}"
        self.finished = True
        return None

    def observed(self) -> None:
        self.ctx.update_memory()

    def annotation(self, t: int) -> dict:
        """The per-frame annotation of frame ``t`` (the observation before action ``t``)."""
        sub = self.task.subtask(self.ctx.intent.subtask)
        return self.writer.frame(t, self.ctx.intent, sub.instruction_idx)


def run_expert_episode(
    task_name: str,
    seed: int,
    split: str = "id",
    on_frame: Callable[[int, ActiveArenaSim, dict, np.ndarray], None] | None = None,
    image_size: tuple[int, int] = HEAD_SIZE,
    search_overshoot: float = 0.0,
    action_noise: float = 0.0,
    decision_period: int = 1,
    press_arm: str | None = None,
    face_jitter: float = 0.0,
    reading_variants: int = 1,
    turn_error: float = 0.0,
    turn_error_subtask: int = 0,
    grasp_miss: float = 0.0,
) -> EpisodeResult:
    """Sample the scene, run the expert until success is reported, it fails or gives up, or the
    step limit; return everything. ``on_frame(t, sim, annotation, action)`` runs before each step
    (e.g. to render video). ``image_size``: the head image's (height, width); the annotations'
    pixel-space fields (boxes, camera intrinsics) follow it. ``search_overshoot``: the probability of a
    recovery demonstration per empty end sector of a search (``ExpertContext``; 0 = the benchmark's
    expert). ``action_noise``: ``ActionNoise``'s sigma in rad (0 = none): ``actions`` stay the expert's,
    ``states`` are where the perturbed commands took the robot. ``decision_period``: the search reacts
    to the view only every that many frames (``ExpertContext``; 1 = the benchmark's expert).
    ``press_arm``: the count-and-press tasks' press with that arm (``ExpertContext``; None = the
    benchmark's expert). ``face_jitter``: ``ExpertContext``'s off-centre demonstrations (rad; 0 = the
    benchmark's expert). ``reading_variants`` N > 1: seed s plays scene s // N with its hidden reading
    shifted by s % N (``DemoVariation``). ``turn_error``: ``TurnError``'s largest angle in rad (0 = none):
    ``actions`` stay the expert's, ``states`` are where the turned torso took the robot;
    ``turn_error_subtask`` K: also the first frames of subtask K (``TurnError``). ``grasp_miss``:
    each pick's first try runs off the expert's command by up to this many m (``ExpertContext``; 0 =
    the benchmark's expert): ``actions`` stay the expert's."""
    t0 = time.perf_counter()
    task = get_task(task_name)
    scene = sample_scene(task, seed // reading_variants, split, reading_shift=seed % reading_variants)
    episode = Episode(task, scene, max_penetration=PENETRATION_LIMIT, image_size=image_size)
    sim = episode.sim
    driver = ExpertDriver(
        task,
        scene,
        sim,
        episode.perception,
        search_overshoot=search_overshoot,
        decision_period=decision_period,
        press_arm=press_arm,
        face_jitter=face_jitter,
        grasp_miss=grasp_miss,
    )
    perturb = ActionNoise(action_noise, seed, task.name) if action_noise else None
    if turn_error_subtask and not 2 <= turn_error_subtask <= len(task.subtasks):
        raise ValueError(
            f"--turn-error-subtask {turn_error_subtask}: {task.name}'s subtasks are 1-{len(task.subtasks)} "
            "and subtask 1 starts the episode"
        )
    turn = TurnError(turn_error, seed, task.name, subtask=turn_error_subtask) if turn_error else None
    frames, actions, states = [], [], []
    failure = None
    for t in range(task.max_episode_steps + 1):
        action = driver.next_action()
        if action is None:
            failure = driver.failure
            break
        if t == task.max_episode_steps:
            failure = f"timeout: the expert needed more than {task.max_episode_steps} steps"
            break
        frame = driver.annotation(t)
        states.append(sim.state())
        frames.append(frame)
        actions.append(action)
        if on_frame is not None:
            on_frame(t, sim, frame, action)
        executed = action
        miss = driver.ctx.executed_offset
        if perturb is not None or turn is not None or miss is not None:  # within the joint limits
            low, high = np.minimum(sim.action_low, action), np.maximum(sim.action_high, action)
            if miss is not None:
                executed = executed + miss
            if perturb is not None:
                executed = perturb(executed, driver.ctx.precise)
            if turn is not None:
                executed = turn(executed, driver.ctx.intent.subtask)
            executed = np.clip(executed, low, high)
        episode.step(executed)
        if episode.physics_problem:
            failure = episode.failure_reason
            break
        if episode.monitor.failure_reason:
            failure = f"task failure: {episode.monitor.failure_reason}"
            break
        if episode.success:
            break
        driver.observed()
    success = episode.success and failure is None
    if failure is None and not success:
        failure = (
            f"task not accomplished when the expert script ended (failed checks: {episode.unmet_checks()})"
        )
    sidecar = make_sidecar(task, scene, driver.writer, episode.perception, driver.ctx, success, failure)
    sidecar["final_checks"] = episode.monitor.checks
    episode.close()
    health = {"max_penetration_m": episode.health.max_penetration, "problem": episode.physics_problem}
    return EpisodeResult(
        task.name,
        seed,
        split,
        success,
        failure,
        np.array(actions),
        np.array(states),
        frames,
        sidecar,
        health,
        time.perf_counter() - t0,
    )
