"""ActiveArena inside allenai's vla-eval harness (``lerobot_activearena/envs/vla_eval_benchmark.py``): the
benchmark class on its own, and ``vla-eval run --no-docker`` on the shipped config against vla-eval's
zero-action reference model server on localhost, read back from vla-eval's aggregate JSON."""

import json
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from lerobot_activearena.envs.gym_ids import STEP_LIMITS
from lerobot_activearena.envs.manifests import manifest_seed
from lerobot_activearena.envs.vla_eval_benchmark import ActiveArenaBenchmark
from lerobot_activearena.tasks import task_names

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "configs" / "vla_eval" / "activearena.yaml"
BIN = Path(sys.executable).parent
TASKS = ("click_bell_rotate_view", "count_target_press_button")  # the config's
ZERO = {"actions": np.zeros(18, np.float32)}


def test_tasks_are_task_split_pairs():
    bench = ActiveArenaBenchmark(tasks="MD", splits="id,ood")
    tasks = bench.get_tasks()
    assert [(t["task"], t["split"]) for t in tasks] == [
        (n, s) for n in task_names("MD") for s in ("id", "ood")
    ]
    assert {t["suite"] for t in tasks} == {"MD"}
    assert tasks[0]["name"] == f"{tasks[0]['task']}_id"
    assert bench.get_metadata()["max_steps"] == max(STEP_LIMITS[n] for n in task_names("MD"))
    with pytest.raises(ValueError, match="splits"):
        ActiveArenaBenchmark(tasks="MD", splits="id,test")


def test_reset_step_result_cycle_is_deterministic():
    bench = ActiveArenaBenchmark(
        tasks="click_bell_rotate_view", splits="id", observation_height=96, observation_width=128
    )
    (task,) = bench.get_tasks()
    task = {**task, "episode_idx": 1}
    try:
        first = bench.make_obs(bench.reset(task), task)
        assert first["images"]["head"].shape == (96, 128, 3) and first["images"]["head"].dtype == np.uint8
        assert first["state"].shape == (18,) and first["state"].dtype == np.float32
        assert first["task_description"] == "Press the bell's top center using the left arm."
        steps = [bench.make_obs(bench.step(ZERO).obs, task) for _ in range(3)]
        cut = bench.get_step_result(bench.step(ZERO))  # the harness's max_steps ends it here
        assert cut["success"] is False and cut["failure_state"] in ("DM", "CO", "CR")
        assert "max_steps" in cut["failure_reason"]
        assert cut["scene_seed"] == manifest_seed("click_bell_rotate_view", "id", 1)
        with pytest.raises(ValueError, match="18-D"):
            bench.step({"actions": np.zeros(7)})

        again = bench.make_obs(bench.reset(task), task)  # same seed -> same episode
        assert np.array_equal(again["images"]["head"], first["images"]["head"])
        for expected in steps:
            obs = bench.make_obs(bench.step(ZERO).obs, task)
            assert np.array_equal(obs["images"]["head"], expected["images"]["head"])
            assert np.array_equal(obs["state"], expected["state"])
        n = 3
        while not bench.check_done(result := bench.step(ZERO)):
            n += 1
        result = bench.get_step_result(result)
        assert n + 1 == STEP_LIMITS["click_bell_rotate_view"]  # zero targets never finish the task
        assert result["success"] is False and result["failure_state"] in ("DM", "CO", "CR")
        assert result["failure_reason"].startswith("step limit")
        assert sum(result[f"failure_{s}"] for s in ("DM", "CO", "CR")) == 1
    finally:
        bench.cleanup()


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _wait_listening(proc: subprocess.Popen, port: int, log: Path, timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            pytest.fail(f"model server exited ({proc.returncode}):\n{log.read_text()[-3000:]}")
        with socket.socket() as s:
            if s.connect_ex(("127.0.0.1", port)) == 0:
                return
        time.sleep(0.2)
    pytest.fail(f"model server not listening on {port} after {timeout}s:\n{log.read_text()[-3000:]}")


def test_vla_eval_run_scores_activearena_episodes(tmp_path):
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    port = _free_port()
    log = tmp_path / "server.log"
    with open(log, "w") as out:
        server = subprocess.Popen(
            [sys.executable, "-m", "vla_eval.model_servers.behavior1k_baseline"]
            + ["--address", f"127.0.0.1:{port}", "--args.action_dim", "18"],
            stdout=out,
            stderr=subprocess.STDOUT,
            env=env,
        )
    try:
        _wait_listening(server, port, log)
        run = subprocess.run(
            [str(BIN / "vla-eval"), "run", "--no-docker", "-c", str(CONFIG)]
            + ["--server-url", f"ws://127.0.0.1:{port}", "--output-dir", str(tmp_path / "out")],
            capture_output=True,
            text=True,
            env=env,
            cwd=tmp_path,
            timeout=600,
        )
    finally:
        server.terminate()
        server.wait(timeout=30)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]

    result = json.loads((tmp_path / "out" / "ActiveArena_aggregate.json").read_text())
    assert result["num_errors"] == 0 and result["num_episodes_total"] == 4
    assert [t["task"] for t in result["tasks"]] == [f"{name}_id" for name in TASKS]
    assert result["mean_success"] == 0.0
    assert result["mean_failure_DM"] + result["mean_failure_CO"] + result["mean_failure_CR"] == 1.0
    for task, name in zip(result["tasks"], TASKS, strict=True):
        assert task["num_episodes"] == 2
        for k, ep in enumerate(sorted(task["episodes"], key=lambda e: e["episode_id"])):
            assert (
                ep["task"] == name and ep["split"] == "id" and "failure_reason" not in ep
            )  # no harness error
            m = ep["metrics"]
            assert m["success"] is False
            assert m["failure_state"] in ("DM", "CO", "CR") and m["failure_reason"]
            assert m["scene_seed"] == manifest_seed(name, "id", k)
            assert ep["steps"] == STEP_LIMITS[name]
