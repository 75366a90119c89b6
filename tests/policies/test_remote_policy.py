"""`activearena_remote` against openpi's own WebsocketPolicyServer on localhost (tests/helpers/
policy_servers.py), no mock of the protocol: a replayed expert scores what the in-process expert
scores, the server receives exactly the documented keys, and a server that fails, hangs or dies gives
an error that names the episodes while the finished ones stay recorded and resume."""

import json
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from lerobot_activearena.cli.eval import main as activearena_eval
from lerobot_activearena.policies.activearena_remote.configuration_activearena_remote import (
    ActiveArenaRemoteConfig,
)
from lerobot_activearena.policies.activearena_remote.modeling_activearena_remote import (
    OBSERVATION_KEYS,
    VLA_EVAL_OBSERVATION_KEYS,
)

SERVERS = Path(__file__).resolve().parents[1] / "helpers" / "policy_servers.py"
TASK = "click_bell_rotate_view"
SMALL = ["--env.observation_height=96", "--env.observation_width=128", "--videos=0", "--workers=1"]


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _serve(kind: str, *args: str, port: int | None = None):
    port = port or _free_port()
    proc = subprocess.Popen([sys.executable, str(SERVERS), kind, str(port), *args])
    deadline = time.time() + 300  # the replay server plays the expert first
    while time.time() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(
                f"the {kind} server exited with {proc.returncode} (openpi-server installed? scripts/bootstrap.sh does)"
            )
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1).close()
            return proc, f"ws://127.0.0.1:{port}"
        except OSError:
            time.sleep(0.5)
    proc.kill()
    raise RuntimeError(f"the {kind} server did not start")


def _records(run: Path) -> list[dict]:
    path = run / "id" / "episodes" / "records.jsonl"
    return [json.loads(x) for x in path.read_text().splitlines()] if path.is_file() else []


def _shard_records(run: Path) -> list[dict]:
    return [json.loads(x) for f in sorted(run.glob("records/**/*.jsonl")) for x in f.read_text().splitlines()]


@pytest.mark.parametrize("protocol", ["openpi", "vla_eval"])
def test_a_replayed_expert_scores_what_the_expert_scores(tmp_path, protocol):
    server, url = _serve(
        "replay" if protocol == "openpi" else "vla_replay", "--task", TASK, "--episodes", "0,1"
    )
    try:
        common = [f"--tasks={TASK}", "--splits=id", "--episodes=2"]
        activearena_eval(
            ["--policy.type=activearena_expert", "--env.render_pixels=false", "--videos=0", "--workers=1"]
            + common
            + [f"--out={tmp_path / 'expert'}"]
        )
        activearena_eval(
            ["--policy.type=activearena_remote", f"--policy.url={url}", f"--policy.protocol={protocol}"]
            + ["--policy.n_action_steps=16"]
            + SMALL
            + common
            + [f"--out={tmp_path / 'remote'}"]
        )
    finally:
        server.kill()
    expert = {r["episode"]: r for r in _records(tmp_path / "expert")}
    remote = {r["episode"]: r for r in _records(tmp_path / "remote")}
    assert sorted(remote) == [0, 1]
    for k in (0, 1):
        assert remote[k]["scene_seed"] == expert[k]["scene_seed"]
        assert remote[k]["success"] and expert[k]["success"], (expert[k], remote[k])


def test_the_server_receives_the_documented_keys(tmp_path):
    log = tmp_path / "received.jsonl"
    server, url = _serve("log", "--log", str(log))
    try:
        activearena_eval(
            ["--policy.type=activearena_remote", f"--policy.url={url}", "--policy.n_action_steps=8"]
            + SMALL
            + [f"--tasks={TASK}", "--splits=id", "--episodes=1", "--env.episode_length=20"]
            + [f"--out={tmp_path / 'run'}"]
        )
    finally:
        server.kill()
    received = [json.loads(x) for x in log.read_text().splitlines()]
    assert [r["activearena/step"]["value"] for r in received] == [0, 8, 16]  # a chunk every 8 steps
    for r in received:
        assert set(r) == set(OBSERVATION_KEYS)
        assert r["observation/image"] == {"type": "ndarray", "dtype": "uint8", "shape": [96, 128, 3]}
        assert r["observation/state"] == {"type": "ndarray", "dtype": "float32", "shape": [18]}
        assert r["prompt"]["value"] == "Press the bell's top center using the left arm."


@pytest.mark.parametrize("kind", ["error", "hang", "die"])
def test_a_failing_server_names_the_episode_and_keeps_finished_ones(tmp_path, kind):
    server, url = _serve(kind)
    run = tmp_path / "run"
    args = (
        ["--policy.type=activearena_remote", f"--policy.url={url}", "--policy.timeout_s=5"]
        + SMALL
        + [f"--tasks={TASK}", "--splits=id", "--episodes=2", "--env.episode_length=40", f"--out={run}"]
    )
    try:
        with pytest.raises(Exception) as failure:
            activearena_eval(args)
    finally:
        server.kill()
    message = str(failure.value) + "".join(
        str(e) for e in (failure.value.__cause__, failure.value.__context__) if e
    )
    expected = {
        "error": "failed on purpose",
        "hang": "did not answer within 5",
        "die": "closed the connection",
    }
    assert expected[kind] in message and "episodes [1] did not finish" in message, message
    assert [r["episode"] for r in _shard_records(run)] == [0]  # the finished episode is kept
    server, _ = _serve("log", "--log", str(tmp_path / "log.jsonl"), port=int(url.rsplit(":", 1)[1]))
    try:  # the same command, the server back up, resumes with the missing episode only
        activearena_eval(args)
    finally:
        server.kill()
    assert sorted(r["episode"] for r in _records(run)) == [0, 1]
    assert json.loads((tmp_path / "log.jsonl").read_text().splitlines()[0])["activearena/step"]["value"] == 0


def test_a_vla_eval_server_receives_the_documented_keys_and_its_errors_are_named(tmp_path):
    log = tmp_path / "received.jsonl"
    server, url = _serve("vla_error", "--log", str(log))
    run = tmp_path / "run"
    args = ["--policy.type=activearena_remote", f"--policy.url={url}", "--policy.protocol=vla_eval", *SMALL]
    args += [f"--tasks={TASK}", "--splits=id", "--episodes=2", "--env.episode_length=3", f"--out={run}"]
    try:
        with pytest.raises(RuntimeError, match=r"(?s)episodes \[1\] did not finish.*failed on purpose"):
            activearena_eval(args)
    finally:
        server.kill()
    received = [json.loads(x) for x in log.read_text().splitlines()]
    assert [next(iter(r)) for r in received[:5]] == [
        "episode_start",
        "images",
        "images",
        "images",
        "episode_start",
    ]
    obs = received[1]
    assert set(obs) == set(VLA_EVAL_OBSERVATION_KEYS)
    assert obs["images"]["value"]["head"] == {"type": "ndarray", "dtype": "uint8", "shape": [96, 128, 3]}
    assert obs["state"] == {"type": "ndarray", "dtype": "float32", "shape": [18]}
    assert obs["task_description"]["value"] == "Press the bell's top center using the left arm."
    assert [r["episode"] for r in _shard_records(run)] == [0]


def test_bad_remote_configs_are_named():
    with pytest.raises(ValueError, match="--policy.url must be a websocket address"):
        ActiveArenaRemoteConfig(url="http://localhost:8000")
    with pytest.raises(ValueError, match="--policy.protocol must be one of"):
        ActiveArenaRemoteConfig(protocol="grpc")
    with pytest.raises(ValueError, match="n_action_steps must be >= 1"):
        ActiveArenaRemoteConfig(n_action_steps=0)


def test_the_docs_tables_are_the_code_tables():
    docs = (Path(__file__).resolve().parents[2] / "docs" / "remote.md").read_text()
    for key, value in {**OBSERVATION_KEYS, **VLA_EVAL_OBSERVATION_KEYS}.items():
        assert f"| `{key}` | {value} |" in docs, key


def test_lerobot_eval_plays_a_remote_policy_with_one_connection_per_env(tmp_path):
    log = tmp_path / "received.jsonl"
    server, url = _serve("log", "--log", str(log))
    exe = Path(sys.executable).with_name("lerobot-eval")
    try:
        subprocess.run(
            [str(exe), "--policy.type=activearena_remote", f"--policy.url={url}", "--policy.device=cpu"]
            + ["--env.type=activearena", f"--env.task={TASK}", "--env.observation_height=96"]
            + ["--env.observation_width=128", "--env.episode_length=20", "--eval.n_episodes=2"]
            + ["--eval.batch_size=2", f"--output_dir={tmp_path / 'eval'}"],
            check=True,
            capture_output=True,
            timeout=600,
        )
    finally:
        server.kill()
    steps = [json.loads(x)["activearena/step"]["value"] for x in log.read_text().splitlines()]
    assert steps == [0, 0, 8, 8, 16, 16]  # two envs, each asking at its chunk boundaries
    info = json.loads((tmp_path / "eval" / "eval_info.json").read_text())
    assert info["overall"]["n_episodes"] == 2
