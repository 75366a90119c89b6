"""What a build makes: the tasks, split and seeds, cut into shards (one per datatrove rank).

With ``episodes`` (N kept episodes per task) the primary seeds are ``seed_start .. seed_start+N-1``
in shards of ``episodes_per_shard``; a shard replaces an expert failure with seeds from its own
reserve block past all primary seeds, so the layout is deterministic and independent of the number
of workers. With explicit ``seeds`` exactly those are tried (failures are skipped and recorded).
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

from ..episodes.rollout import DemoVariation
from ..sim.head_camera import validate_head_size
from ..sim.scene import HEAD_SIZE
from ..tasks import get_task, task_names
from ..tasks.base import SPLITS


@dataclass(frozen=True)
class ShardSpec:
    rank: int
    task: str
    seeds: tuple[int, ...]  # tried first, in order
    reserve: tuple[int, ...]  # tried after failures until ``quota`` episodes are kept
    quota: int

    @property
    def name(self) -> str:
        return f"{self.rank:05d}-{self.task}"


@dataclass
class BuildPlan:
    repo_id: str
    split: str
    tasks: list[str]
    episodes: int | None = None
    seeds: list[int] | None = None
    seed_start: int = 0
    episodes_per_shard: int = 10
    max_objects: int = 16
    image_size: tuple[int, int] = HEAD_SIZE  # head video (height, width), 3:4
    search_overshoot: float = 0.0  # recovery demonstrations (``ExpertContext``); 0: the benchmark's expert
    action_noise: float = 0.0  # perturbed demonstrations (``ActionNoise``), rad; 0: the benchmark's expert
    decision_period: int = 1  # chunk-aligned demonstrations (``ExpertContext``); 1: the benchmark's expert
    press_arm: str | None = None  # one-arm count presses (``ExpertContext``); None: the benchmark's expert
    face_jitter: float = 0.0  # off-centre demonstrations (``ExpertContext``), rad; 0: the benchmark's expert
    reading_variants: int = 1  # counterfactual readings (``DemoVariation``); 1: the benchmark's scenes
    turn_error: float = 0.0  # turn-recovery demonstrations (``TurnError``), rad; 0: the benchmark's expert
    turn_error_subtask: int = 0  # ... also at this subtask's start (``TurnError``); 0: none
    grasp_miss: float = 0.0  # grasp-retry demonstrations (``ExpertContext``), m; 0: the benchmark's expert
    shards: list[ShardSpec] = field(init=False)

    def __post_init__(self):
        if self.split not in SPLITS:
            raise ValueError(f"split must be one of {SPLITS}, got {self.split!r}")
        if (self.episodes is None) == (self.seeds is None):
            raise ValueError("give exactly one of --episodes N (kept episodes per task) or --seeds a,b,c")
        if self.episodes is not None and self.episodes < 1:
            raise ValueError(f"--episodes must be >= 1, got {self.episodes}")
        if self.seeds is not None and (
            not self.seeds or len(set(self.seeds)) != len(self.seeds) or min(self.seeds) < 0
        ):
            raise ValueError(f"--seeds must be distinct non-negative integers, got {self.seeds}")
        if self.episodes_per_shard < 1:
            raise ValueError(f"--episodes-per-shard must be >= 1, got {self.episodes_per_shard}")
        self.image_size = validate_head_size(*self.image_size)
        _ = self.variation  # validates its values
        self.tasks = [t for sel in self.tasks for t in task_names(sel)]
        if self.turn_error_subtask:
            short = [t for t in self.tasks if len(get_task(t).subtasks) < self.turn_error_subtask]
            if short:
                raise ValueError(
                    f"--turn-error-subtask {self.turn_error_subtask}: {short} have fewer subtasks; "
                    "give a subtask number every task of the build has"
                )
        if self.reading_variants > 1:  # refused here, not seed by seed in the shards
            from ..tasks.sampling import sample_scene

            for task in self.tasks:  # raises for a task that draws no reading
                sample_scene(get_task(task), 0, self.split, reading_shift=1)
        self.shards = self._make_shards()

    def _make_shards(self) -> list[ShardSpec]:
        shards: list[ShardSpec] = []
        size = self.episodes_per_shard
        for task in self.tasks:
            if self.seeds is not None:
                primary = list(self.seeds)
            else:
                primary = list(range(self.seed_start, self.seed_start + self.episodes))
            reserve_base = self.seed_start + len(primary)
            for j in range(0, len(primary), size):
                chunk = tuple(primary[j : j + size])
                reserve = (
                    ()
                    if self.seeds is not None
                    else tuple(range(reserve_base + j, reserve_base + j + len(chunk)))
                )
                shards.append(ShardSpec(len(shards), task, chunk, reserve, len(chunk)))
        return shards

    @property
    def variation(self) -> DemoVariation:
        return DemoVariation(
            search_overshoot=self.search_overshoot,
            action_noise=self.action_noise,
            decision_period=self.decision_period,
            press_arm=self.press_arm,
            face_jitter=self.face_jitter,
            reading_variants=self.reading_variants,
            turn_error=self.turn_error,
            turn_error_subtask=self.turn_error_subtask,
            grasp_miss=self.grasp_miss,
        )

    def to_json(self) -> dict:
        from .features import dataset_features  # the feature set is part of a build's identity

        d = asdict(self)
        # builds made before an option keep their identity: a default value is not written
        for key, default in asdict(DemoVariation()).items():
            if d[key] == default:
                del d[key]
        d["features"] = json.loads(json.dumps(dataset_features(self.max_objects, self.image_size)))
        d["shards"] = [asdict(s) for s in self.shards]
        return d

    def save(self, path: Path) -> None:
        path.write_text(json.dumps(self.to_json(), indent=1))

    def same_as(self, path: Path) -> bool:
        return json.loads(path.read_text()) == json.loads(json.dumps(self.to_json()))
