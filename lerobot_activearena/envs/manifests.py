"""Evaluation seed manifests: per task and split, 100 ordered unique scene seeds that a
simulator-only run (the scripted expert, no policy) verified as valid and solvable. The protocol
evaluates the first 50.

Evaluation seeds are drawn from ``EVAL_SEED_START`` upwards so they never coincide with the seeds
dataset builds use for training episodes (0 upwards).
"""

from __future__ import annotations

import json
from pathlib import Path

MANIFEST_DIR = Path(__file__).with_name("seed_manifests")  # one JSON per task
EVAL_SEED_START = 100_000
MANIFEST_SIZE = 100
PROTOCOL_EPISODES = 50
DEFAULT_SEED_BASE = 1000  # lerobot-eval's default --seed: episode k of a run plays seed DEFAULT_SEED_BASE + k


def manifest_path(task: str) -> Path:
    return MANIFEST_DIR / f"{task}.json"


def load_manifest(task: str, split: str) -> list[int]:
    path = manifest_path(task)
    if not path.exists():
        raise FileNotFoundError(
            f"no seed manifest for task {task!r} ({path}); generate it with "
            f"`activearena-make-manifests --tasks {task}`"
        )
    data = json.loads(path.read_text())
    if split not in data["splits"]:
        raise KeyError(f"manifest {path} has no split {split!r}; it has {sorted(data['splits'])}")
    return list(data["splits"][split]["seeds"])


def manifest_seed(task: str, split: str, episode: int) -> int:
    """The scene seed of evaluation episode ``episode`` (0-based) of ``task``/``split``."""
    seeds = load_manifest(task, split)
    if not 0 <= episode < len(seeds):
        raise IndexError(
            f"episode {episode} is outside the {len(seeds)}-seed manifest of {task}/{split}; "
            f"the protocol evaluates episodes 0..{PROTOCOL_EPISODES - 1} (lerobot-eval --seed must equal "
            f"the env's seed_base, and --eval.n_episodes <= {len(seeds)})"
        )
    return seeds[episode]
