"""Shared fixtures. Importing the discovery shim registers the env and policy types as LeRobot's
CLIs do. Expensive artefacts are built once per test session: the expert episodes (``expert_episode``)
and a small builder dataset (``bell_count_dataset``)."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import pytest  # noqa: E402

import lerobot_activearena  # noqa: E402,F401  (selects the GL backend before mujoco loads)
import lerobot_env_activearena  # noqa: E402,F401  (registers the env and policy types, as LeRobot's CLIs do)

BELL, COUNT = "click_bell_rotate_view", "count_target_press_button"
DATASET_REPO = "local/bench_id"


@pytest.fixture(scope="session")
def expert_episode():
    """``expert_episode(task, seed, split)``: the scripted expert's episode, run once per session."""
    from lerobot_activearena.tasks.rollout import run_expert_episode

    cache = {}

    def get(task: str, seed: int, split: str = "id"):
        key = (task, int(seed), split)
        if key not in cache:
            cache[key] = run_expert_episode(task, int(seed), split)
        return cache[key]

    return get


@pytest.fixture(scope="session")
def bell_count_dataset(tmp_path_factory):
    """The bell and count tasks, one episode each, two shards built by two datatrove worker processes
    through ``activearena-build-dataset`` (repo id ``DATASET_REPO``). Read-only for the tests."""
    from lerobot_activearena.cli.build_dataset import main as build_main

    root = tmp_path_factory.mktemp("ds") / "bench_id"
    build_main(
        ["--repo-id", DATASET_REPO, "--root", str(root), "--tasks", f"{BELL},{COUNT}", "--episodes", "1"]
        + ["--episodes-per-shard", "1", "--workers", "2"]
    )
    return root
