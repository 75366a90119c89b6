"""What an ``activearena-eval`` run evaluates: tasks x splits x manifest episodes, cut into shards
(one per datatrove rank), for one policy, and the run folder that holds it.

The protocol is every task x {ID, OOD} x the first 50 episodes of each seed manifest. A shard is
one task and split and a block of ``episodes_per_shard`` manifest episodes, longest tasks first; the
layout depends only on the selection, never on the number of workers, so a run can resume on another
machine.

Run folder::

    run.json                  the plan (its identity decides whether a folder may be resumed)
    policy/config.json        the policy config every shard builds its policy from
    records/<shard>/*.jsonl   one line per finished episode, written as each episode ends
    videos/                   rollout videos (the first episodes of each shard)
    logs/                     datatrove logs and completions
    <split>/eval_info.json    after the merge: lerobot-eval's layout, plus <split>/episodes/
    report/                   the leaderboard report of this run
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

from ..envs.manifests import DEFAULT_SEED_BASE, PROTOCOL_EPISODES, load_manifest
from ..tasks import get_task, task_names
from ..tasks.base import SPLITS

RUN_FILE = "run.json"


def register_policy_types() -> None:
    """Every policy type lerobot-eval knows: LeRobot's built-in ones (importing ``lerobot.policies``
    registers their configs) and those of installed plugins (``lerobot_policy_*`` / ``lerobot_env_*``
    distributions, this project's included), found as lerobot-eval finds them."""
    import lerobot.policies  # noqa: F401
    from lerobot.utils.import_utils import register_third_party_plugins

    register_third_party_plugins()


def uses_expert_channel(policy_type: str | None) -> bool:
    """Only the scripted oracle gets the env's privileged expert channel."""
    return policy_type == "activearena_expert"


@dataclass(frozen=True)
class EvalShard:
    rank: int
    task: str
    split: str
    episodes: tuple[int, ...]  # manifest indices

    @property
    def name(self) -> str:
        return f"{self.rank:05d}-{self.task}-{self.split}"


@dataclass
class EvalPlan:
    label: str
    policy: dict  # the policy config (config.json contents)
    policy_path: str | None  # pretrained weights (Hub id or local folder); None builds from scratch
    tasks: list[str]
    splits: list[str]
    episodes: list[int] = field(default_factory=lambda: list(range(PROTOCOL_EPISODES)))
    fixed_view: bool = False
    env: dict = field(
        default_factory=dict
    )  # further ActiveArenaEnvConfig options (render_pixels, episode_length)
    seed_base: int = DEFAULT_SEED_BASE
    episodes_per_shard: int = PROTOCOL_EPISODES
    shards: list[EvalShard] = field(init=False)

    def __post_init__(self):
        bad = [s for s in self.splits if s not in SPLITS]
        if bad or not self.splits:
            raise ValueError(f"unknown split(s) {bad or self.splits}: use a comma list of {SPLITS}")
        self.tasks = [t for sel in self.tasks for t in task_names(sel)]
        if not self.episodes or len(set(self.episodes)) != len(self.episodes) or min(self.episodes) < 0:
            raise ValueError(f"episodes must be distinct manifest indices >= 0, got {self.episodes}")
        if self.episodes_per_shard < 1:
            raise ValueError(f"--episodes-per-shard must be >= 1, got {self.episodes_per_shard}")
        for task in self.tasks:
            for split in self.splits:
                n = len(load_manifest(task, split))
                if max(self.episodes) >= n:
                    raise ValueError(
                        f"episode {max(self.episodes)} is outside the {n}-seed manifest of {task}/{split}; "
                        f"the protocol evaluates episodes 0..{PROTOCOL_EPISODES - 1}"
                    )
        self.shards = self._make_shards()

    def _make_shards(self) -> list[EvalShard]:
        """Longest tasks first (by step limit), so the last shards to start are short ones and the
        workers finish together."""
        shards: list[EvalShard] = []
        size = self.episodes_per_shard
        longest_first = sorted(self.tasks, key=lambda t: (-get_task(t).max_episode_steps, t))
        for task in longest_first:
            for split in self.splits:
                for j in range(0, len(self.episodes), size):
                    shards.append(EvalShard(len(shards), task, split, tuple(self.episodes[j : j + size])))
        return shards

    @property
    def n_episodes(self) -> int:
        return len(self.tasks) * len(self.splits) * len(self.episodes)

    def category(self, task: str) -> str:
        return get_task(task).category

    # ---- persistence ----------------------------------------------------------------------------
    def to_json(self) -> dict:
        d = asdict(self)
        d["shards"] = [asdict(s) for s in self.shards]
        return json.loads(json.dumps(d))

    @classmethod
    def from_json(cls, d: dict) -> EvalPlan:
        kwargs = {k: v for k, v in d.items() if k != "shards"}
        return cls(**kwargs)

    @classmethod
    def load(cls, run_dir: Path) -> EvalPlan:
        return cls.from_json(json.loads((Path(run_dir) / RUN_FILE).read_text()))

    def differences(self, other: dict) -> list[str]:
        """Fields in which a saved plan differs from this one (the label does not count)."""
        mine = self.to_json()
        keys = sorted((set(mine) | set(other)) - {"label"})
        return [k for k in keys if mine.get(k) != other.get(k)]
