"""`activearena-build-dataset`: a real sharded build opened by unmodified LeRobot, its columns
checked against the expert, resume after SIGKILL, skipped seeds, Hub upload, LeRobot's own CLIs."""

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import torch
from helpers.fake_slurm import install_fake_slurm, submitted_jobs
from helpers.params import BELL, COUNT, DATASET_REPO
from lerobot.datasets.dataset_metadata import LeRobotDatasetMetadata
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.scripts.lerobot_dataset_viz import main as dataset_viz_main
from lerobot.scripts.lerobot_edit_dataset import main as edit_dataset_main

from lerobot_activearena.annotations.keyframes import chunk_keyframes, motion_keyframes, subtask_keyframes
from lerobot_activearena.cli.build_dataset import main as build_main, make_plan, parser
from lerobot_activearena.datasets_build import shard as shard_mod
from lerobot_activearena.datasets_build.features import (
    IMAGE_KEY,
    MASK_PAD,
    MAX_OBJECTS,
    dataset_features,
    matrix,
)
from lerobot_activearena.datasets_build.pipeline import build_dataset, push
from lerobot_activearena.datasets_build.plan import BuildPlan
from lerobot_activearena.datasets_build.record import record_episode
from lerobot_activearena.envs.manifests import EVAL_SEED_START, load_manifest
from lerobot_activearena.episodes.rollout import DemoVariation
from lerobot_activearena.tasks import get_task, task_names

RECIPES = Path(__file__).parents[2] / "datasets_build"
HISTORY = [-16 * k / 15 for k in range(12, -1, -1)]  # stride-16 history of 12 frames + the current one


def _exe(name):
    return shutil.which(name, path=str(Path(sys.executable).parent)) or shutil.which(name)


@pytest.fixture(scope="module")
def built(bell_count_dataset):
    """Two tasks, one episode each, two shards built by two datatrove worker processes."""
    return bell_count_dataset


def _parse_build_args(argv):
    return parser().parse_args(argv)


def _episodes(root):
    return [json.loads(line) for line in (root / "meta/activearena/episodes.jsonl").read_text().splitlines()]


def test_dataset_opens_in_lerobot_with_stride16_history(built):
    meta = LeRobotDatasetMetadata("local/bench_id", root=built)
    eps = _episodes(built)
    assert meta.total_episodes == 2 and meta.fps == 15 and meta.robot_type == "astribot_s1"
    assert [e["task"] for e in eps] == [BELL, COUNT] and [e["seed"] for e in eps] == [0, 0]
    assert [int(e["length"]) for e in meta.episodes] == [e["length"] for e in eps]
    assert all("/" not in k for k in meta.features)
    assert set(dataset_features()) <= set(meta.features) and meta.video_keys == [IMAGE_KEY]
    ds = LeRobotDataset(
        "local/bench_id",
        root=built,
        video_backend="pyav",
        delta_timestamps={IMAGE_KEY: HISTORY, "observation.state": HISTORY},
    )
    first_len = eps[0]["length"]
    item = ds[first_len + 50]  # frame 50 of the second episode
    assert item[IMAGE_KEY].shape == (13, 3, 384, 512) and item["observation.state"].shape == (13, 18)
    # frames 50 - 16k exist for k <= 3; the other 9 history slots are padding
    assert item[f"{IMAGE_KEY}_is_pad"].tolist() == [True] * 9 + [False] * 4
    assert item["episode_index"] == 1 and item["frame_index"] == 50
    sidecar = json.loads((built / "meta/activearena/sidecars/episode_000001.json").read_text())
    assert item["task"] == sidecar["instruction"]
    # the history is the real past: the stored state 16 frames earlier
    assert np.allclose(
        item["observation.state"][-2].numpy(), ds.hf_dataset[first_len + 34]["observation.state"].numpy()
    )


def test_columns_match_the_expert_and_keyframe_definitions(built, expert_episode):
    ds = LeRobotDataset("local/bench_id", root=built, video_backend="pyav")
    first, ep = _episodes(built)  # the second is the count task: several objects, subtask changes
    ref = expert_episode(ep["task"], ep["seed"], "id")  # deterministic: same seed, same trajectory
    length = ref.length
    rows = ds.hf_dataset.with_format("numpy")[first["length"] : first["length"] + length]
    assert (rows["episode_index"] == 1).all() and len(rows["frame_index"]) == length
    assert np.array_equal(rows["action"], ref.actions.astype(np.float32))
    assert np.array_equal(rows["observation.state"], ref.states.astype(np.float32))
    n = len(ref.sidecar["objects"])
    visible = np.stack(rows["visible_object_mask"])
    assert visible.shape == (length, MAX_OBJECTS) and (visible[:, n:] == MASK_PAD).all()
    assert np.array_equal(visible[:, :n], np.stack([f["visible_object_mask"] for f in ref.frames]))
    assert np.array_equal(rows["subtask_index"].ravel(), [f["subtask"] for f in ref.frames])
    theta = np.array([f["camera_target_theta"] for f in ref.frames])
    assert np.array_equal(rows["camera_target_active"].ravel(), np.isfinite(theta).astype(np.int8))
    assert np.allclose(rows["camera_target_theta"].ravel()[np.isfinite(theta)], theta[np.isfinite(theta)])
    assert np.allclose(matrix(rows, "extrinsic_cv")[7], ref.frames[7]["extrinsic_cv"])
    assert np.array_equal(
        rows["subtask_keyframe"].ravel(), subtask_keyframes([f["subtask"] for f in ref.frames])
    )
    assert np.array_equal(rows["motion_keyframe"].ravel(), motion_keyframes(ref.states))
    assert np.array_equal(rows["chunk_keyframe"].ravel(), chunk_keyframes(length))
    assert rows["subtask_keyframe"].sum() >= 2  # the count task changes subtask at least once


def test_video_frames_are_the_head_camera_images(built):
    ds = LeRobotDataset("local/bench_id", root=built, video_backend="pyav")
    rec = record_episode(BELL, 0, "id")
    for t in (0, 77, rec.result.length - 1):
        decoded = (ds[t][IMAGE_KEY].numpy().transpose(1, 2, 0) * 255).astype(np.float32)
        err = np.abs(decoded - rec.images[t].astype(np.float32)).mean()
        assert err < 6.0, f"frame {t}: mean abs error {err:.1f} (lossy AV1 should stay well below 6)"


def test_a_slow_video_encoder_drops_no_frame(tmp_path, monkeypatch):
    """LeRobot's streaming encoder is made for live recording: a frame that waits more than 0.1 s
    for a place in its queue is dropped, and every later frame of the video then shows the wrong
    step. A build adds a whole episode at once; on a busy machine (here: the encoder thread made
    slower than 0.1 s per frame) the video must still hold every frame, in order."""
    import threading

    import av
    from lerobot.datasets import video_utils

    real = video_utils.Image.fromarray

    def slow(*args, **kwargs):  # the encoder thread turns each frame into an image first
        if threading.current_thread() is not threading.main_thread():
            time.sleep(0.12)
        return real(*args, **kwargs)

    monkeypatch.setattr(video_utils.Image, "fromarray", slow)
    spec = shard_mod.ShardSpec(rank=0, task=BELL, seeds=(0,), reserve=(), quota=1)
    summary = shard_mod.build_shard(spec, "id", "local/slow", tmp_path, 16, image_size=(96, 128))
    (video,) = (tmp_path / "shards" / spec.name / "videos").rglob("*.mp4")
    with av.open(str(video)) as container:
        frames = sum(1 for _ in container.decode(video=0))
    assert frames == summary["kept"][0]["length"] > 60


def test_lerobots_default_decoder_reads_the_history(built):
    """The set-up installs FFmpeg's shared libraries, so LeRobot's default decoder (torchcodec)
    loads, and it reads the same 13-frame history as PyAV."""
    from lerobot.utils.import_utils import get_safe_default_video_backend

    assert get_safe_default_video_backend() == "torchcodec", "torchcodec could not load FFmpeg's libraries"
    delta = {IMAGE_KEY: HISTORY, "observation.state": HISTORY}
    default = LeRobotDataset("local/bench_id", root=built, delta_timestamps=delta)
    pyav = LeRobotDataset("local/bench_id", root=built, video_backend="pyav", delta_timestamps=delta)
    a, b = default[60][IMAGE_KEY].numpy(), pyav[60][IMAGE_KEY].numpy()
    assert a.shape == b.shape == (13, 3, 384, 512)
    assert np.abs(a - b).mean() * 255 < 1.0


def test_meta_folder_records_seeds_sidecars_and_plan(built):
    build = json.loads((built / "meta/activearena/build.json").read_text())
    assert build["episodes"] == 2 and build["skipped"] == 0 and build["plan"]["split"] == "id"
    assert build["frames"] == sum(e["length"] for e in _episodes(built))
    side = json.loads((built / "meta/activearena/sidecars/episode_000000.json").read_text())
    assert side["task"] == BELL and side["seed"] == 0 and side["success"]
    assert {"instruction", "objects", "subtasks", "transitions", "final_discovered"} <= set(side)
    assert (built / "meta/activearena/skipped.jsonl").read_text() == ""
    assert not built.with_name(built.name + ".work").exists()  # shards are removed after the merge


def test_release_recipes_are_the_papers_training_set_and_a_preview_of_it():
    train = make_plan(_parse_build_args(["--recipe", str(RECIPES / "train_id.json"), "--root", "/tmp/x"]))
    assert train.tasks == task_names("all") and train.split == "id" and train.repo_id.endswith("_train_id")
    for task in train.tasks:  # 100 solved ID episodes per task, seeds 0-99, failures replaced from 100-199
        shards = [s for s in train.shards if s.task == task]
        assert sum(s.quota for s in shards) == 100
        assert sorted(x for s in shards for x in s.seeds) == list(range(100))
        assert sorted(x for s in shards for x in s.reserve) == list(range(100, 200))
        # no training scene is an evaluation scene
        assert all(min(load_manifest(task, split)) >= EVAL_SEED_START for split in ("id", "ood"))
    preview = make_plan(_parse_build_args(["--recipe", str(RECIPES / "preview.json"), "--root", "/tmp/x"]))
    assert preview.tasks == train.tasks and all(s.seeds == (0, 1) for s in preview.shards)
    # a flag on the command line wins over the recipe
    small = make_plan(
        _parse_build_args(["--recipe", str(RECIPES / "preview.json"), "--root", "/x", "--tasks", BELL])
    )
    assert small.tasks == [BELL] and small.repo_id == preview.repo_id


def test_dataset_card_describes_the_build(built):
    from huggingface_hub import DatasetCard

    card = DatasetCard.load(built / "README.md")
    info = json.loads((built / "meta/info.json").read_text())
    build = json.loads((built / "meta/activearena/build.json").read_text())
    eps = _episodes(built)
    assert card.data.license == "apache-2.0" and {"LeRobot", "activearena"} <= set(card.data.tags)
    assert card.data.configs[0]["data_files"] == "data/*/*.parquet"
    text = card.text
    # tasks by category, each row from the episodes it holds
    assert "### SS: single-object search (1 of the paper's 5 tasks)" in text
    assert "### MD: multi-object decision (1 of the paper's 3 tasks)" in text
    for e in eps:
        sidecar = json.loads(
            (built / f"meta/activearena/sidecars/episode_{e['episode_index']:06d}.json").read_text()
        )
        row = f"| `{e['task']}` | {get_task(e['task']).max_episode_steps} | 1 | {e['length']} | {e['seed']} | 0 |"
        assert row + f" {sidecar['instruction']} |" in text
    for name, ft in info["features"].items():  # every feature, with its dtype and shape
        assert f"| `{name}` | {ft['dtype']} | {tuple(ft['shape'])} |" in text
    assert "`motion_keyframe`: frame 0 plus causally confirmed motion events" in text
    assert "Evaluation manifests draw seeds from 100000 up" in text
    # the command that made it, the recipe it came from and what the command line changed
    assert build["command"].startswith("activearena-build-dataset --recipe") and build["command"] in text
    assert "datasets_build/preview.json" in text and "overrode `--repo-id`, `--tasks`, `--episodes`" in text
    assert f"LeRobot {build['lerobot_version']}" in text and f"MuJoCo {build['versions']['mujoco']}" in text
    assert "title  = {ActiveArena: Benchmarking and Understanding Active Perception" in text


def test_lerobots_streaming_dataset_reads_the_build(built):
    from lerobot.datasets.streaming_dataset import StreamingLeRobotDataset

    stream = StreamingLeRobotDataset(DATASET_REPO, root=built, shuffle=False)
    first = next(iter(stream))
    ds = LeRobotDataset(DATASET_REPO, root=built, video_backend="pyav")
    assert stream.num_episodes == 2 and stream.num_frames == ds.num_frames
    ref = ds[int(first["index"])]
    assert torch.equal(first["action"], ref["action"]) and first["task"] == ref["task"]
    assert first[IMAGE_KEY].shape == ref[IMAGE_KEY].shape == (3, 384, 512)


def test_failed_expert_episodes_are_skipped_recorded_and_replaced(tmp_path, monkeypatch):
    real = shard_mod.record_episode

    def flaky(task, seed, split, image_size, variation):
        rec = real(task, seed, split, image_size, variation)
        if seed == 0:
            rec.result.success, rec.result.failure = False, "forced failure for the test"
        return rec

    monkeypatch.setattr(shard_mod, "record_episode", flaky)
    plan = BuildPlan(repo_id="local/flaky", split="id", tasks=[BELL], episodes=2, episodes_per_shard=2)
    assert plan.shards[0].seeds == (0, 1) and plan.shards[0].reserve == (2, 3)
    summary = build_dataset(plan, tmp_path / "flaky", workers=1, progress=False)
    assert summary["episodes"] == 2 and summary["skipped"] == 1
    assert [e["seed"] for e in _episodes(tmp_path / "flaky")] == [1, 2]  # seed 0 replaced by reserve seed 2
    skipped = [
        json.loads(line)
        for line in (tmp_path / "flaky/meta/activearena/skipped.jsonl").read_text().splitlines()
    ]
    assert skipped == [{"task": BELL, "seed": 0, "split": "id", "reason": "forced failure for the test"}]


def test_killed_build_resumes_and_keeps_finished_shards(tmp_path):
    root, work = tmp_path / "resume", tmp_path / "resume.work"
    cmd = [
        _exe("activearena-build-dataset"),
        "--repo-id",
        "local/resume",
        "--root",
        str(root),
        "--tasks",
        BELL,
        "--episodes",
        "3",
        "--episodes-per-shard",
        "1",
        "--workers",
        "1",
        "--keep-shards",
    ]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    first = work / "shards" / f"00000-{BELL}" / "shard.json"
    deadline = time.time() + 300
    while not first.exists() and time.time() < deadline:
        time.sleep(0.2)
    assert first.exists(), "the first shard never completed"
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    assert not root.exists()  # the dataset folder only appears complete
    stamp = first.stat().st_mtime_ns
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    assert "3 episodes" in out.stdout
    meta = LeRobotDatasetMetadata("local/resume", root=root)
    assert meta.total_episodes == 3 and [e["seed"] for e in _episodes(root)] == [0, 1, 2]
    assert first.stat().st_mtime_ns == stamp  # the shard finished before the kill was kept, not rebuilt
    # a second identical command is a no-op on a complete dataset
    again = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0 and "3 episodes" in again.stdout


def test_resume_does_not_rebuild_completed_shards(tmp_path, monkeypatch):
    plan = BuildPlan(repo_id="local/partial", split="id", tasks=[BELL], episodes=2, episodes_per_shard=1)
    work = tmp_path / "partial.work"
    work.mkdir()
    plan.save(work / "plan.json")
    shard_mod.build_shard(
        plan.shards[0], "id", plan.repo_id, work, plan.max_objects
    )  # as if killed after shard 0
    stamp = (work / "shards" / plan.shards[0].name / "shard.json").stat().st_mtime_ns
    calls = []
    real = shard_mod.record_episode
    monkeypatch.setattr(shard_mod, "record_episode", lambda *a: calls.append(a) or real(*a))
    summary = build_dataset(
        plan, tmp_path / "partial", work_dir=work, workers=1, keep_shards=True, progress=False
    )
    assert calls == [(BELL, 1, "id", (384, 512), DemoVariation())]  # only the missing shard ran
    assert (work / "shards" / plan.shards[0].name / "shard.json").stat().st_mtime_ns == stamp
    assert summary["episodes"] == 2


def test_refuses_to_overwrite_other_data(tmp_path):
    other = tmp_path / "other"
    other.mkdir()
    (other / "precious.txt").write_text("keep me")
    plan = BuildPlan(repo_id="local/x", split="id", tasks=[BELL], episodes=1)
    with pytest.raises(FileExistsError, match="--overwrite"):
        build_dataset(plan, other, workers=1, progress=False)
    assert (other / "precious.txt").read_text() == "keep me"
    work = tmp_path / "w"
    work.mkdir()
    BuildPlan(repo_id="local/x", split="ood", tasks=[BELL], episodes=1).save(work / "plan.json")
    with pytest.raises(FileExistsError, match="different arguments"):
        build_dataset(plan, tmp_path / "new", work_dir=work, workers=1, progress=False)


def test_bad_arguments_get_clear_errors():
    with pytest.raises(ValueError, match="split"):
        BuildPlan(repo_id="a/b", split="test", tasks=[BELL], episodes=1)
    with pytest.raises(ValueError, match="exactly one"):
        BuildPlan(repo_id="a/b", split="id", tasks=[BELL])
    with pytest.raises(ValueError, match="unknown task"):
        BuildPlan(repo_id="a/b", split="id", tasks=["nope"], episodes=1)
    with pytest.raises(SystemExit):
        build_main(["--repo-id", "a/b", "--root", "/tmp/x", "--episodes", "0"])
    explicit = BuildPlan(
        repo_id="a/b", split="id", tasks=[BELL, COUNT], seeds=[5, 9, 11], episodes_per_shard=2
    )
    assert [(s.task, s.seeds, s.reserve) for s in explicit.shards] == [
        (BELL, (5, 9), ()),
        (BELL, (11,), ()),
        (COUNT, (5, 9), ()),
        (COUNT, (11,), ()),
    ]


@pytest.mark.parametrize(
    ("key", "value", "flag", "bad"),
    [
        ("search_overshoot", 0.5, "1", 1.5),
        ("action_noise", 0.02, "0.03", 0.5),
        ("decision_period", 16, "8", 0),
        ("press_arm", "left", "right", "both"),
        ("face_jitter", 0.1, "0.15", 0.5),
        ("reading_variants", 3, "2", 0),
        ("turn_error", 0.3, "0.2", 0.5),
        ("grasp_miss", 0.05, "0.04", 0.2),
    ],
)
def test_demonstration_variations_are_an_opt_in_part_of_the_plan(tmp_path, key, value, flag, bad):
    plan = make_plan(
        _parse_build_args(["--repo-id", "a/b", "--root", "/x", "--tasks", BELL, "--episodes", "1"])
    )
    default = getattr(DemoVariation(), key)
    assert getattr(plan, key) == default and key not in plan.to_json()  # old builds resume
    recipe = tmp_path / "r.json"
    task = "check_block_color" if key == "reading_variants" else BELL  # a task with a reading to vary
    recipe.write_text(json.dumps({"repo_id": "a/b", "tasks": task, "episodes": 1, key: value}))
    from_recipe = make_plan(_parse_build_args(["--recipe", str(recipe), "--root", "/x"]))
    assert getattr(from_recipe, key) == value and from_recipe.to_json()[key] == value
    assert getattr(from_recipe.variation, key) == value  # what the shards' expert runs with
    option = "--" + key.replace("_", "-")
    flagged = make_plan(_parse_build_args(["--recipe", str(recipe), "--root", "/x", option, flag]))
    assert getattr(flagged, key) == type(value)(flag)
    plan.save(tmp_path / "plan.json")
    assert not flagged.same_as(tmp_path / "plan.json")  # a resume with another value is refused
    with pytest.raises(ValueError, match=option):
        BuildPlan(repo_id="a/b", split="id", tasks=[BELL], episodes=1, **{key: bad})


def test_turn_error_subtask_is_a_recipe_key_and_a_flag_checked_against_the_tasks(tmp_path):
    """The place's turn error rides with --turn-error in the plan (an old build's plan omits it) and
    is refused for a task without that subtask."""
    recipe = tmp_path / "r.json"
    task = "check_block_color"
    recipe.write_text(json.dumps({"repo_id": "a/b", "tasks": task, "episodes": 1, "turn_error": 0.3}))
    plain = make_plan(_parse_build_args(["--recipe", str(recipe), "--root", "/x"]))
    assert plain.turn_error_subtask == 0 and "turn_error_subtask" not in plain.to_json()
    flagged = make_plan(
        _parse_build_args(["--recipe", str(recipe), "--root", "/x", "--turn-error-subtask", "4"])
    )
    assert flagged.variation.turn_error_subtask == 4 and flagged.to_json()["turn_error_subtask"] == 4
    plain.save(tmp_path / "plan.json")
    assert not flagged.same_as(tmp_path / "plan.json")
    with pytest.raises(ValueError, match="fewer subtasks"):
        BuildPlan(repo_id="a/b", split="id", tasks=[BELL], episodes=1, turn_error=0.3, turn_error_subtask=2)


def test_bad_recipes_get_clear_errors(tmp_path, capsys):
    def error_of(recipe: dict | None, *argv):
        path = tmp_path / "r.json"
        if recipe is not None:
            path.write_text(json.dumps(recipe))
        with pytest.raises(SystemExit):
            build_main(["--recipe", str(path), "--root", str(tmp_path / "ds"), *argv])
        return capsys.readouterr().err

    assert "no recipe at" in error_of(None)
    assert "unknown key(s) ['episode']" in error_of({"repo_id": "a/b", "episode": 3})
    assert "both 'episodes' and 'seeds'" in error_of({"repo_id": "a/b", "episodes": 3, "seeds": [1]})
    assert "--repo-id is required" in error_of({"tasks": BELL, "episodes": 1})
    assert not (tmp_path / "ds").exists()


def test_push_to_hub_uses_lerobots_upload_path(built, monkeypatch, tmp_path):
    from huggingface_hub import HfApi
    from huggingface_hub.repocard import RepoCard

    calls = {}

    def record(name):
        def fn(self, *args, **kwargs):
            calls.setdefault(name, []).append(kwargs)
            if name == "upload_folder":
                shutil.copytree(kwargs["folder_path"], tmp_path / "hub", dirs_exist_ok=True)

        return fn

    for name in (
        "create_repo",
        "upload_folder",
        "upload_file",
        "create_commit",
        "create_tag",
        "delete_tag",
        "create_branch",
    ):
        monkeypatch.setattr(HfApi, name, record(name))
    monkeypatch.setattr(
        RepoCard, "validate", lambda self, *a, **k: calls.setdefault("card", []).append(self.content)
    )
    push("local/bench_id", built)
    assert (
        calls["create_repo"][0]["repo_type"] == "dataset"
        and calls["create_repo"][0]["repo_id"] == "local/bench_id"
    )
    assert Path(calls["upload_folder"][0]["folder_path"]) == built
    assert (tmp_path / "hub/meta/activearena/build.json").exists() and (
        tmp_path / "hub/meta/info.json"
    ).exists()
    assert any((tmp_path / "hub/videos").rglob("*.mp4"))
    # LeRobot's card template with the build's card: our tags, tasks table and citation
    pushed = calls["card"][0]
    assert "activearena" in pushed and "| `click_bell_rotate_view` | 137 | 1 |" in pushed
    assert pushed == (built / "README.md").read_text()


def _run_cli(monkeypatch, main, *argv):
    """A LeRobot console script in this process: its own argument parsing, no fresh import of torch."""
    monkeypatch.setattr(sys, "argv", [main.__module__, *argv])
    main()


def test_lerobot_edit_dataset_info_and_merge(built, tmp_path, monkeypatch, capsys):
    _run_cli(
        monkeypatch,
        edit_dataset_main,
        "--repo_id",
        "local/bench_id",
        "--root",
        str(built),
        "--operation.type",
        "info",
    )
    info = capsys.readouterr().out
    frames = json.loads((built / "meta/activearena/build.json").read_text())["frames"]
    assert "Total episode: 2" in info and f"({frames})" in info and "FPS: 15" in info
    merged = tmp_path / "merged"
    _run_cli(
        monkeypatch,
        edit_dataset_main,
        "--new_repo_id",
        "local/merged",
        "--new_root",
        str(merged),
        "--operation.type",
        "merge",
        "--operation.repo_ids",
        "['local/bench_id', 'local/bench_id2']",
        "--operation.roots",
        f"['{built}', '{built}']",
    )
    meta = LeRobotDatasetMetadata("local/merged", root=merged)
    assert meta.total_episodes == 4 and set(dataset_features()) <= set(meta.features)


def test_lerobot_dataset_viz_saves_a_recording(built, tmp_path, monkeypatch):
    _run_cli(
        monkeypatch,
        dataset_viz_main,
        "--repo-id",
        "local/bench_id",
        "--root",
        str(built),
        "--episode-index",
        "0",
        "--mode",
        "local",
        "--save",
        "1",
        "--output-dir",
        str(tmp_path),
        "--num-workers",
        "0",
    )
    rrd = list(tmp_path.glob("*.rrd"))
    assert rrd and rrd[0].stat().st_size > 100_000


def test_slurm_executor_builds_through_array_jobs_and_a_dependent_merge(tmp_path, monkeypatch):
    install_fake_slurm(tmp_path, monkeypatch)
    plan = BuildPlan(repo_id="local/slurm", split="id", tasks=[BELL], episodes=2, episodes_per_shard=1)
    out = build_dataset(
        plan,
        tmp_path / "slurm",
        executor="slurm",
        slurm={"partition": "cpu", "time": "00:30:00"},
        progress=False,
    )
    assert out is None  # submitted; the merge job writes the dataset
    jobs = submitted_jobs(tmp_path)
    shards = next(j for j in jobs if "activearena-build" in j["script"] and "--array=0-1" in j["script"])
    merge = next(
        j for j in jobs if "activearena-build-merge" in j["script"] and "merge_stats" not in j["script"]
    )
    assert "#SBATCH --partition=cpu" in shards["script"]
    assert f"--dependency=afterok:{shards['job']}" in merge["args"]
    meta = LeRobotDatasetMetadata("local/slurm", root=tmp_path / "slurm")
    assert meta.total_episodes == 2 and [e["seed"] for e in _episodes(tmp_path / "slurm")] == [0, 1]


def test_a_recorded_episode_replayed_through_the_env_is_the_same_episode(bell_count_dataset, expert_episode):
    """What a policy learns from is what the env shows: frame t of the dataset holds the state and
    the head image the env shows before action t, and action t is the expert's command there. The
    expert's actions replayed through the gym env at the episode's seed give the same episode; the
    stored float32 actions (what any policy outputs) still solve it, within 2 steps of the record
    (the rounding, ~1e-8 rad, moves the gripper's contact with the bell by up to 0.03 rad)."""
    from lerobot_activearena.envs.gym_env import ActiveArenaEnv

    ds = LeRobotDataset(DATASET_REPO, root=bell_count_dataset)
    episodes = [json.loads(line) for line in (bell_count_dataset / "meta/activearena/episodes.jsonl").open()]
    for ep in episodes:
        start = ds.meta.episodes["dataset_from_index"][ep["episode_index"]]
        frames = [ds[start + t] for t in range(ep["length"])]
        expert = expert_episode(ep["task"], ep["seed"], ep["split"])
        stored = np.stack([f["action"].numpy() for f in frames])
        np.testing.assert_array_equal(stored, expert.actions.astype(np.float32))
        env = ActiveArenaEnv(ep["task"], split=ep["split"], use_manifest=False)
        obs, _ = env.reset(seed=ep["seed"])
        for t, frame in enumerate(frames):
            np.testing.assert_array_equal(obs["agent_pos"], frame["observation.state"].numpy())
            image = frame["observation.images.head"].permute(1, 2, 0).numpy() * 255
            assert np.abs(image - obs["pixels"]["head"]).mean() < 4.0, (ep["task"], t)  # AV1 loss only
            obs, _, terminated, _, info = env.step(expert.actions[t])
            assert info["is_success"] == (t == ep["length"] - 1), (ep["task"], t)
        assert terminated
        obs, _ = env.reset(seed=ep["seed"])
        for t in range(env._max_episode_steps):
            obs, _, terminated, truncated, info = env.step(stored[min(t, len(stored) - 1)])
            if terminated or truncated:
                break
        assert info["is_success"] and abs(t + 1 - ep["length"]) <= 2, (ep["task"], t + 1, ep["length"])
        env.close()
