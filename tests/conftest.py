"""Shared fixtures. Importing the discovery shim registers the env and policy types as LeRobot's
CLIs do. Expensive artefacts are built once per test session: the expert episodes (``expert_episode``)
and a small builder dataset (``bell_count_dataset``)."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")
if os.environ.get("PYTEST_XDIST_WORKER"):  # one core per worker: torch, BLAS and Mesa's rasteriser
    for var in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "LP_NUM_THREADS"):
        os.environ.setdefault(var, "1")

# first: selects the GL backend before mujoco is imported
import lerobot_activearena  # noqa: E402,F401,I001
import pytest  # noqa: E402
import torch  # noqa: E402

if os.environ.get("PYTEST_XDIST_WORKER"):
    torch.set_num_threads(1)

from helpers.params import BELL, COUNT, DATASET_REPO, PREVIEW_RECIPE  # noqa: E402

import lerobot_env_activearena  # noqa: E402,F401  (registers the env and policy types, as LeRobot's CLIs do)


@pytest.fixture(scope="session")
def expert_episode():
    """``expert_episode(task, seed, split)``: the scripted expert's episode, run once per session."""
    from lerobot_activearena.episodes.rollout import run_expert_episode

    cache = {}

    def get(task: str, seed: int, split: str = "id"):
        key = (task, int(seed), split)
        if key not in cache:
            cache[key] = run_expert_episode(task, int(seed), split)
        return cache[key]

    return get


@pytest.fixture(scope="session")
def tiny_vlm(tmp_path_factory):
    """A tiny random Qwen3-VL folder (``--policy.vlm_path``), its tokenizer knowing every task's words."""
    from lerobot_activearena.policies.activearena_vla.tiny_vlm import make_tiny_vlm
    from lerobot_activearena.tasks.registry import task_texts

    return make_tiny_vlm(tmp_path_factory.mktemp("vlm") / "tiny_qwen3_vl", texts=task_texts())


@pytest.fixture(scope="session")
def bell_count_dataset(tmp_path_factory, worker_id):
    """The preview release recipe (``datasets_build/preview.json``) on a small scale: the bell and
    count tasks, one episode each, two shards built by two datatrove worker processes through
    ``activearena-build-dataset`` (repo id ``DATASET_REPO``); built once for all xdist workers.
    Read-only for the tests."""
    from filelock import FileLock

    from lerobot_activearena.cli.build_dataset import main as build_main

    shared = tmp_path_factory.getbasetemp()
    if worker_id != "master":
        shared = shared.parent  # the run's folder, above each worker's own
    root = shared / "bell_count_dataset" / "bench_id"
    with FileLock(str(shared / "bell_count_dataset.lock")):
        if not (root / "meta" / "activearena" / "build.json").exists():
            build_main(
                ["--recipe", str(PREVIEW_RECIPE), "--repo-id", DATASET_REPO, "--root", str(root)]
                + ["--tasks", f"{BELL},{COUNT}"]
                + ["--episodes", "1", "--episodes-per-shard", "1", "--workers", "2"]
            )
    return root


# ---- the suite's cost per registered task ----------------------------------------------------------
_DURATIONS: dict[str, float] = {}


def pytest_runtest_logreport(report):
    _DURATIONS[report.nodeid] = _DURATIONS.get(report.nodeid, 0.0) + report.duration


def pytest_terminal_summary(terminalreporter):
    """Test time (setup + call + teardown, summed over workers) that grows with the task registry:
    the test functions parametrised over every registered task, and that time per task."""
    from lerobot_activearena.tasks import task_names

    tasks = task_names("all")
    if not _DURATIONS:
        return
    by_function: dict[str, dict[str, float]] = {}
    for nodeid, seconds in _DURATIONS.items():
        function, _, params = nodeid.split("@")[0].partition("[")  # loadgroup appends "@<group>"
        task = next((t for t in tasks if t in params.rstrip("]").split("-")), None)
        if task is not None:
            per = by_function.setdefault(function, {})
            per[task] = per.get(task, 0.0) + seconds
    per_task = {f: per for f, per in by_function.items() if set(per) == set(tasks)}
    if not per_task:  # a selection without the per-task tests
        return
    total = sum(_DURATIONS.values())
    tasked = sum(sum(per.values()) for per in per_task.values())
    costs = dict.fromkeys(tasks, 0.0)
    for per in per_task.values():
        for t, sec in per.items():
            costs[t] += sec
    slowest = sorted(costs.items(), key=lambda kv: -kv[1])[:3]
    terminalreporter.write_sep("-", "test time per registered task")
    terminalreporter.write_line(
        f"{total:.0f} s of test time (all workers); {tasked:.0f} s in {len(per_task)} test functions run "
        f"for every task: {tasked / len(tasks):.1f} s per task x {len(tasks)} tasks; slowest: "
        + ", ".join(f"{t} {sec:.1f} s" for t, sec in slowest)
    )
    heaviest = sorted(per_task.items(), key=lambda kv: -sum(kv[1].values()))[:6]
    terminalreporter.write_line(
        "per task, by test function: "
        + ", ".join(f"{f.split('::')[-1]} {sum(per.values()) / len(tasks):.1f} s" for f, per in heaviest)
    )
