"""The expert's working state: the current command, what it declares (intent), and what it has seen."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

from ..annotations.writer import Intent
from ..sim.action import HEAD_PITCH, TORSO_YAW
from ..sim.head_camera import search_views
from ..sim.perception import PerceptionMemory
from ..sim.simulator import ActiveArenaSim
from .gaze import Gaze
from .ik import ArmIK
from .motion import with_arm


class ExpertError(RuntimeError):
    """The scripted expert cannot finish this episode (object not found, grasp lost, IK failure)."""


MAX_FACE_JITTER = 0.2  # rad: beyond it objects at the fan's edge fall out of the arm's reach
MAX_GRASP_MISS = 0.08  # m: the largest offset of a missed first grasp (``grasp_miss``)

PRESS_ARMS = (
    None,
    "left",
    "right",
)  # ``press_arm``: None is the benchmark's expert (the arm on the button's half)


class ExpertContext:
    """Shared by all primitives of one episode. Search decisions read only ``memory`` (positions of
    objects the camera has seen); manipulation reads the true pose of an object once it is known."""

    def __init__(
        self,
        sim: ActiveArenaSim,
        objects: list[str],
        perception: PerceptionMemory,
        ik: ArmIK,
        gaze: Gaze,
        n_subtasks: int = 1,
        search_overshoot: float = 0.0,
        rng: np.random.Generator | None = None,
        decision_period: int = 1,
        press_arm: str | None = None,
        face_jitter: float = 0.0,
        face_rng: np.random.Generator | None = None,
        grasp_miss: float = 0.0,
        miss_rng: np.random.Generator | None = None,
    ):
        if not isinstance(decision_period, int) or decision_period < 1:
            raise ValueError(f"decision_period is a number of frames >= 1, got {decision_period!r}")
        if not 0.0 <= search_overshoot <= 1.0:
            raise ValueError(f"search_overshoot is a probability in [0, 1], got {search_overshoot}")
        if not 0.0 <= face_jitter <= MAX_FACE_JITTER:
            raise ValueError(f"face_jitter is an angle in [0, {MAX_FACE_JITTER}] rad, got {face_jitter}")
        if search_overshoot > 0.0 and rng is None:
            raise ValueError("search_overshoot > 0 needs an rng (seeded from the scene seed)")
        if face_jitter > 0.0 and face_rng is None:
            raise ValueError("face_jitter > 0 needs a face_rng (seeded from the scene seed)")
        if not 0.0 <= grasp_miss <= MAX_GRASP_MISS:
            raise ValueError(f"grasp_miss is a distance in [0, {MAX_GRASP_MISS}] m, got {grasp_miss}")
        if grasp_miss > 0.0 and miss_rng is None:
            raise ValueError("grasp_miss > 0 needs a miss_rng (seeded from the scene seed)")
        self.sim, self.perception, self.ik, self.gaze = sim, perception, ik, gaze
        # Recovery demonstrations for datasets (0 = the benchmark's expert): the probability that a
        # search sweep that found nothing in an end sector goes on to the torso's joint limit before it
        # turns back, so a memory-free policy sees what to do after an overshoot (``search``).
        self.search_overshoot, self.rng = search_overshoot, rng
        # Chunk-aligned demonstrations for datasets (1 = the benchmark's expert): the search reacts to
        # what the camera shows only at frames that are multiples of this period, where a policy that
        # executes chunks of that many actions open-loop plans its next chunk (``search``).
        self.decision_period = decision_period
        # One-arm demonstrations for datasets (None = the benchmark's expert): the count-and-press
        # tasks press with this arm wherever the button is, not with the arm on its half of the fan,
        # so which arm moves does not depend on the count (the click_bell expert's one arm).
        if press_arm not in PRESS_ARMS:
            raise ValueError(f"press_arm is 'left', 'right' or None, got {press_arm!r}")
        self.press_arm = press_arm
        # Off-centre demonstrations for datasets (0 = the benchmark's expert): each turn that puts an
        # object in front of an arm (``view_moves.face_for_arm``) is off by a uniform angle in
        # +/- this many rad, and the arm reaches from there, so the arm's path depends on where the
        # object sits in the view, not only on the torso's heading.
        self.face_jitter, self.face_rng = face_jitter, face_rng
        # Grasp-retry demonstrations for datasets (0 = the benchmark's expert): each pick's first try
        # runs with the arm off the expert's command (``executed_offset``), up to this many m above
        # and beside the grasp point; it closes on nothing, and the expert lets go and grasps again
        # (``skills.pick``), so a policy sees what to do after a missed grasp.
        self.grasp_miss, self.miss_rng = grasp_miss, miss_rng
        # added to the command the simulator executes, not to the one recorded (dataset builds only)
        self.executed_offset: np.ndarray | None = None
        self.n_subtasks = n_subtasks
        self.objects = list(objects)
        self.info = {o.name: o for o in sim.info.objects}
        self.action = sim.home_action()
        self.intent = Intent()
        self.memory: dict[int, np.ndarray] = {}  # object index -> centre when last seen
        self.views = search_views(sim.info.workspace)  # (torso yaw, head pitch) per search sector
        self.explored: set[int] = set()  # sector ids (indices into ``views``) swept so far
        self.notes: dict = {}  # what the expert inferred (colours, counts), for the sidecar
        self.frame = 0  # index of the next emitted action (= the episode frame it is applied at)
        # arm side -> (joint waypoints left, gripper) of a motion it makes while the script commands
        # something else (an arm going home while the other one works)
        self.trailing: dict[str, tuple[list[np.ndarray], float | None]] = {}
        # inside a contact stroke that must land where it is aimed (a press): perturbed demonstrations
        # (``episodes.rollout.ActionNoise``) fade their offset out here
        self.precise = False

    @contextmanager
    def subtask(self, k: int):
        """Frames emitted inside the block are annotated as subtask ``k`` (the task's k-th declared
        subtask, 1-based)."""
        if not 1 <= k <= self.n_subtasks:
            raise ValueError(f"subtask {k} is not declared (the task has {self.n_subtasks})")
        self.intent.subtask = k
        yield

    @contextmanager
    def precision(self):
        """Frames emitted inside the block belong to a contact stroke (``precise``)."""
        self.precise = True
        try:
            yield
        finally:
            self.precise = False

    # ---- objects -----------------------------------------------------------------------------
    def idx(self, name: str) -> int:
        if name not in self.objects:
            raise ExpertError(f"the scene has no object {name!r}")
        return self.objects.index(name)

    def obj(self, i: int):
        return self.info[self.objects[i]]

    def pose(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        body = self.sim.data.body(self.obj(i).body)
        return body.xpos.copy(), body.xmat.reshape(3, 3).copy()

    def center(self, i: int) -> np.ndarray:
        p, rot = self.pose(i)
        return p + rot @ np.asarray(self.obj(i).center_offset)

    def top_z(self, i: int) -> float:
        return float(self.center(i)[2] + self.obj(i).half_extents[2])

    def bottom_z(self, i: int) -> float:
        """Lowest point of the object's bounding box (a carried object may hang tilted)."""
        p, rot = self.pose(i)
        return float(self.center(i)[2] - np.abs(rot[2]) @ np.asarray(self.obj(i).half_extents))

    def update_memory(self) -> None:
        for i in np.flatnonzero(self.perception.visible):
            self.memory[int(i)] = self.center(int(i))

    # ---- command -----------------------------------------------------------------------------
    @property
    def yaw(self) -> float:
        return float(self.action[TORSO_YAW])

    @property
    def pitch(self) -> float:
        return float(self.action[HEAD_PITCH])

    def emit(self) -> np.ndarray:
        for side, (path, gripper) in list(self.trailing.items()):
            self.action = with_arm(self.action, side, path.pop(0), gripper)
            if not path:
                del self.trailing[side]
        self.frame += 1
        return self.action.copy()

    def deciding(self) -> bool:
        """Whether the next emitted action starts a decision period (``decision_period``)."""
        return self.frame % self.decision_period == 0

    def await_decision(self) -> Iterator[np.ndarray]:
        """Hold the command until the next action starts a decision period (none for period 1)."""
        while not self.deciding():
            yield self.emit()

    def overshoots(self, sector: int) -> bool:
        """Whether this empty end sector's sweep goes on to the joint limit (``search_overshoot``)."""
        if self.search_overshoot == 0.0 or self.views[sector][0] == 0.0:
            return False  # no draw: the default expert's episodes are unchanged
        return bool(self.rng.random() < self.search_overshoot)

    def face_offset(self) -> float:
        """The torso's offset (rad) for the next turn that faces an object for an arm (``face_jitter``)."""
        if self.face_jitter == 0.0:
            return 0.0  # no draw: the default expert's episodes are unchanged
        return float(self.face_rng.uniform(-self.face_jitter, self.face_jitter))

    def require_idle(self, side: str) -> None:
        """Raise if the ``side`` arm is still making a trailing motion (``motion.await_trailing``)."""
        if side in self.trailing:
            raise ExpertError(
                f"the {side} arm is commanded while its trailing motion runs: await or halt it first"
            )
