"""`activearena-eval`: sharded, resumable protocol runs through LeRobot's rollout loop, merged into
lerobot-eval's layout; the configs/env files in lerobot-eval; Slurm through a fake sbatch; bad input."""

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import draccus
import pytest
from helpers.fake_slurm import install_fake_slurm, submitted_jobs
from helpers.params import BELL, COUNT
from lerobot.configs.eval import EvalPipelineConfig
from lerobot.configs.types import FeatureType, PolicyFeature
from lerobot.scripts.lerobot_eval import main as lerobot_eval_cli

from lerobot_activearena.cli.eval import main as eval_main
from lerobot_activearena.envs.manifests import load_manifest
from lerobot_activearena.eval.protocol import EvalPlan
from lerobot_activearena.eval.runner import run_eval
from lerobot_activearena.eval.shard import read_records
from lerobot_activearena.policies.activearena_expert.configuration_activearena_expert import (
    ActiveArenaExpertConfig,
)
from lerobot_activearena.tasks import get_task

ROOT = Path(__file__).resolve().parents[2]
EXPERT = ["--policy.type=activearena_expert", "--policy.device=cpu", "--env.render_pixels=false"]


def _exe(name):
    return shutil.which(name, path=str(Path(sys.executable).parent)) or shutil.which(name)


@pytest.fixture(scope="module")
def protocol_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("eval") / "expert"
    eval_main(
        [*EXPERT, "--tasks", f"{BELL},{COUNT}", "--splits", "id,ood", "--episodes", "2", "--out", str(out)]
    )
    return out


def test_merged_results_are_lerobot_eval_output_per_split(protocol_run):
    for split in ("id", "ood"):
        info = json.loads((protocol_run / split / "eval_info.json").read_text())
        tasks = {e["task_id"]: e for e in info["per_task"]}
        assert set(tasks) == {BELL, COUNT}
        assert tasks[BELL]["task_group"] == "SS" and tasks[COUNT]["task_group"] == "MD"
        assert tasks[BELL]["metrics"]["successes"] == [True, True]  # the oracle solves its manifest seeds
        assert info["per_group"]["SS"]["n_episodes"] == 2 and info["overall"]["n_episodes"] == 4
        assert info["overall"]["pc_success"] == 100.0
        video = Path(tasks[COUNT]["metrics"]["video_paths"][0])
        assert video.name == f"{COUNT}_{split}_000.mp4" and video.stat().st_size > 10_000
        recs = [
            json.loads(line)
            for line in (protocol_run / split / "episodes" / "records.jsonl").read_text().splitlines()
        ]
        assert len(recs) == 4
        for r in recs:  # one record per episode, with what the report and the chunk metric need
            assert r["split"] == split and r["scene_seed"] == load_manifest(r["task"], split)[r["episode"]]
            assert r["failure_state"] == "" and r["steps"] == len(r["view_targets"]) > 16
    header, row = [
        line.split(",") for line in (protocol_run / "report" / "leaderboard.csv").read_text().splitlines()
    ]
    board = dict(zip(header, row, strict=True))
    assert (
        board["policy"] == "activearena_expert" and float(board["SS ID"]) == float(board["MD OOD"]) == 100.0
    )
    assert board["SL ID"] == ""  # no SL task in this run
    assert "activearena_expert ID" in (protocol_run / "report" / "per_task.csv").read_text()


def test_rerunning_a_finished_run_plays_nothing_and_refuses_another_configuration(protocol_run, capsys):
    stamp = {p: p.stat().st_mtime_ns for p in (protocol_run / "records").rglob("*.jsonl")}
    eval_main(
        [
            *EXPERT,
            "--tasks",
            f"{BELL},{COUNT}",
            "--splits",
            "id,ood",
            "--episodes",
            "2",
            "--workers",
            "8",
            "--out",
            str(protocol_run),
        ]
    )
    assert {p: p.stat().st_mtime_ns for p in (protocol_run / "records").rglob("*.jsonl")} == stamp
    # 4 shards (task x split) for 8 workers: the user learns how to use them all
    assert "keep only 4 of the 8 workers busy" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        eval_main(
            [*EXPERT, "--tasks", BELL, "--splits", "id,ood", "--episodes", "3", "--out", str(protocol_run)]
        )
    err = capsys.readouterr().err
    assert "another configuration" in err and "episodes" in err and "tasks" in err and "--overwrite" in err


def test_env_processes_play_the_same_episodes_as_one_process(protocol_run, tmp_path):
    eval_main(
        [
            *EXPERT,
            "--tasks",
            BELL,
            "--splits",
            "id",
            "--episodes",
            "2",
            "--batch-size",
            "2",
            "--async-envs",
            "--videos",
            "0",
            "--out",
            str(tmp_path / "async"),
        ]
    )
    ours = read_records(tmp_path / "async" / "records")
    assert (
        len({f.name for f in (tmp_path / "async" / "records").rglob("*.jsonl")}) == 2
    )  # one file per env process
    one = read_records(protocol_run / "records")
    for key, rec in ours.items():
        assert {k: rec[k] for k in ("scene_seed", "steps", "success", "view_targets")} == {
            k: one[key][k] for k in ("scene_seed", "steps", "success", "view_targets")
        }


def test_killed_run_resumes_without_losing_or_repeating_episodes(tmp_path):
    n = 10
    out = tmp_path / "run"
    cmd = [
        _exe("activearena-eval"),
        *EXPERT,
        "--tasks",
        COUNT,
        "--splits",
        "id",
        "--episodes",
        str(n),
        "--batch-size",
        "2",
        "--videos",
        "0",
        "--out",
        str(out),
    ]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.time() + 300
    # killed after 2 finished episodes; 10 in all, so that a busy machine's late poll still finds it half way
    while time.time() < deadline and len(read_records(out / "records")) < 2:
        time.sleep(0.2)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    before = read_records(out / "records")
    assert 2 <= len(before) < n, "the run should be killed half way"
    assert not (out / "id" / "eval_info.json").exists()
    resumed = subprocess.run(cmd, check=True, capture_output=True, text=True, timeout=600)
    # a clean terminal: progress bars and a summary; datatrove's logs and stats go to the run folder,
    # and no warning about normalisation statistics for the expert, which normalises nothing
    console = resumed.stdout + resumed.stderr
    assert f"success over {n} episodes" in console
    assert "Stats" not in console and "PIPELINE" not in console and "infinite values" not in console
    assert (out / "logs" / "executor.log").is_file() and list((out / "logs" / "logs").glob("task_*.log"))
    lines = [
        json.loads(line) for f in (out / "records").rglob("*.jsonl") for line in f.read_text().splitlines()
    ]
    assert sorted(r["episode"] for r in lines) == list(range(n))  # each once: none lost, none re-run
    after = read_records(out / "records")
    assert all(after[k] == v for k, v in before.items())  # the finished episodes were kept as they were
    info = json.loads((out / "id" / "eval_info.json").read_text())
    assert info["per_task"][0]["metrics"]["successes"] == [True] * n


def test_a_finished_shard_missing_records_plays_them_again(protocol_run, tmp_path):
    """A shard datatrove marked complete whose records lack an episode (its line deleted, or skipped
    as another process's record) plays that episode again when the command is re-run, and only it."""
    out = tmp_path / "run"
    shutil.copytree(protocol_run, out)
    (shard_file,) = (out / "records").glob(f"*{COUNT}-ood/*.jsonl")
    lines = shard_file.read_text().splitlines()
    shard_file.write_text(lines[0] + "\n")
    lost = json.loads(lines[1])["episode"]
    eval_main(
        [*EXPERT, "--tasks", f"{BELL},{COUNT}", "--splits", "id,ood", "--episodes", "2", "--out", str(out)]
    )
    records = [json.loads(x) for f in (out / "records").rglob("*.jsonl") for x in f.read_text().splitlines()]
    keys = [(r["task"], r["split"], r["episode"]) for r in records]
    assert len(keys) == len(set(keys)) == 8  # the lost one played again, nothing else re-ran
    again = read_records(out / "records")[(COUNT, "ood", lost)]
    assert again == read_records(protocol_run / "records")[(COUNT, "ood", lost)]
    info = json.loads((out / "ood" / "eval_info.json").read_text())
    assert sum(len(t["metrics"]["successes"]) for t in info["per_task"]) == 4


def test_slurm_runs_shards_as_array_jobs_then_a_dependent_merge(tmp_path, monkeypatch):
    install_fake_slurm(tmp_path, monkeypatch)
    cfg = ActiveArenaExpertConfig(device="cpu")
    cfg._save_pretrained(tmp_path)
    policy = json.loads((tmp_path / "config.json").read_text())
    plan = EvalPlan(
        label="expert",
        policy=policy,
        policy_path=None,
        tasks=[BELL],
        splits=["id"],
        episodes=[0, 1],
        env={"render_pixels": False},
        episodes_per_shard=1,
    )
    assert (
        run_eval(
            plan,
            tmp_path / "run",
            policy,
            executor="slurm",
            progress=False,
            slurm={"partition": "gpu", "time": "01:00:00", "gpus_per_task": 1},
        )
        is None
    )
    jobs = submitted_jobs(tmp_path)
    shards = next(j for j in jobs if "activearena-eval" in j["script"] and "--array=0-1" in j["script"])
    merge = next(
        j for j in jobs if "activearena-eval-merge" in j["script"] and "merge_stats" not in j["script"]
    )
    assert "#SBATCH --partition=gpu" in shards["script"] and "#SBATCH --gpus=1" in shards["script"]
    assert f"--dependency=afterok:{shards['job']}" in merge["args"]
    info = json.loads((tmp_path / "run" / "id" / "eval_info.json").read_text())  # written by the merge job
    assert info["per_task"][0]["metrics"]["successes"] == [True, True]


@pytest.mark.parametrize(
    "name", ["activearena_id", "activearena_ood", "activearena_fixed_id", "activearena_fixed_ood"]
)
def test_env_configs_are_lerobot_eval_configs_of_the_protocol(name):
    cfg = draccus.parse(
        EvalPipelineConfig,
        config_path=ROOT / "configs" / "env" / f"{name}.json",
        args=["--policy.type=activearena_expert"],
    )
    assert cfg.env.type == "activearena" and cfg.env.task == "all" and cfg.eval.n_episodes == 50
    assert cfg.env.split == name.rsplit("_", 1)[1] and cfg.env.fixed_view == ("fixed" in name)
    assert cfg.seed == cfg.env.seed_base  # episode k of lerobot-eval plays manifest seed k


def test_fixed_view_config_runs_in_lerobot_eval(tmp_path, monkeypatch):
    """lerobot-eval's entry point (its own parsing of ``--config_path``) in this process."""
    monkeypatch.setattr(
        sys,
        "argv",
        [
            "lerobot-eval",
            f"--config_path={ROOT / 'configs/env/activearena_fixed_ood.json'}",
            "--policy.type=activearena_expert",
            "--policy.device=cpu",
            f"--env.task={BELL}",
            "--env.expert_channel=true",
            "--env.render_pixels=false",
            "--env.episode_length=20",
            f"--env.episode_log_dir={tmp_path / 'eval' / 'episodes'}",
            "--eval.n_episodes=1",
            f"--output_dir={tmp_path / 'eval'}",
        ],
    )
    lerobot_eval_cli()
    rec = json.loads((next((tmp_path / "eval" / "episodes").glob("*.jsonl"))).read_text().splitlines()[0])
    assert rec["fixed_view"] is True and rec["split"] == "ood" and rec["episode"] == 0 and rec["steps"] == 20
    assert {tuple(v) for v in rec["view_targets"]} == {(0.0, 1.0)}  # torso and head held at home


def test_bad_input_gets_errors_that_name_the_fix(tmp_path, capsys):
    def error(*args):
        with pytest.raises(SystemExit):
            eval_main([*args, "--out", str(tmp_path / "bad")])
        return capsys.readouterr().err

    assert "unknown task selector 'no_such_task'" in error(*EXPERT, "--tasks", "no_such_task")
    assert "unknown split(s) ['train']" in error(*EXPERT, "--splits", "id,train")
    assert "--policy.path=" in error("--tasks", BELL)
    assert "use --tasks, --splits" in error(*EXPERT, "--env.split=ood")
    assert "outside the 100-seed manifest" in error(*EXPERT, "--episode-indices", "99-100")
    wrong = ActiveArenaExpertConfig(
        device="cpu",
        input_features={
            "observation.images.wrist": PolicyFeature(type=FeatureType.VISUAL, shape=(3, 224, 224)),
            "observation.state": PolicyFeature(type=FeatureType.STATE, shape=(14,)),
        },
        output_features={"action": PolicyFeature(type=FeatureType.ACTION, shape=(18,))},
    )
    (tmp_path / "ckpt").mkdir()
    wrong._save_pretrained(tmp_path / "ckpt")
    err = error(f"--policy.path={tmp_path / 'ckpt'}", "--tasks", BELL)
    assert "do not match" in err and "observation.images.wrist (3, 224, 224) is not provided" in err
    assert "observation.state has shape (18,) in the env, (14,) in the policy" in err
    assert not (tmp_path / "bad").exists()  # nothing started


def test_shards_depend_on_the_selection_not_on_workers():
    plan = EvalPlan(
        label="x",
        policy={"type": "activearena_expert"},
        policy_path=None,
        tasks=["SS"],
        splits=["id", "ood"],
        episodes=list(range(5)),
        episodes_per_shard=2,
    )
    n_tasks = len(plan.tasks)
    assert len(plan.shards) == 2 * n_tasks * 3 and plan.n_episodes == 2 * n_tasks * 5
    first = [s for s in plan.shards if s.task == plan.shards[0].task]
    assert [(s.split, s.episodes) for s in first] == [
        ("id", (0, 1)),
        ("id", (2, 3)),
        ("id", (4,)),
        ("ood", (0, 1)),
        ("ood", (2, 3)),
        ("ood", (4,)),
    ]
    limits = [get_task(s.task).max_episode_steps for s in plan.shards]
    assert limits == sorted(limits, reverse=True)  # longest tasks start first
    again = EvalPlan.from_json(plan.to_json())
    assert again.shards == plan.shards and again.differences(plan.to_json()) == []


def test_policy_counts_stop_at_each_episodes_last_step():
    """LeRobot's rollout steps a batch until its last env ends: an env that ended at step 1 gets the
    counts it had then, not the ones its ignored later chunks added."""
    import torch

    from lerobot_activearena.eval.shard import stats_at_episode_ends

    snapshots = [[{"chunks": t + 1}, {"chunks": t + 1}, {"chunks": 1}] for t in range(4)]
    done = torch.tensor([[0, 1, 1, 1], [0, 0, 0, 1], [0, 0, 0, 0]], dtype=torch.bool)  # env 2 truncated
    assert stats_at_episode_ends(snapshots, done) == [{"chunks": 2}, {"chunks": 4}, {"chunks": 1}]


def test_a_worker_loads_the_policy_once_per_plan_and_each_shard_starts_from_the_same_rng(tmp_path):
    """loaded_policy: the next shard of the same plan reuses the loaded policy and starts from the RNG
    state that loading left (as a fresh worker would); another plan loads its own."""
    import torch

    from lerobot_activearena.eval.shard import forget_loaded_policy, loaded_policy

    loads = []

    def load():
        loads.append(torch.rand(1))  # loading draws random numbers (a policy built from scratch)
        return object(), "pre", "post"

    plan = EvalPlan(label="a", policy={"type": "act"}, policy_path=None, tasks=[BELL], splits=["id"])
    first = loaded_policy(tmp_path, plan, load)
    after_load = torch.rand(3)
    torch.rand(100)  # the first shard's rollouts
    again = loaded_policy(tmp_path, plan, load)
    assert again is first and len(loads) == 1
    assert torch.equal(torch.rand(3), after_load)
    other = EvalPlan(label="b", policy={"type": "diffusion"}, policy_path=None, tasks=[BELL], splits=["id"])
    assert loaded_policy(tmp_path, other, load) is not first and len(loads) == 2
    forget_loaded_policy()  # the run ended (or a shard failed): the next run loads afresh
    loaded_policy(tmp_path, other, load)
    assert len(loads) == 3
