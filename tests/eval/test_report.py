"""`activearena-report` on hand-made lerobot-eval outputs with known answers."""

import gzip
import json
import os
import re

import numpy as np
import pytest

from lerobot_activearena.cli.report import main
from lerobot_activearena.eval.report import chunk_jump_deg, mean_chunk_jump


def _run(root, split, results, failures):
    """results: {(category, task): [success, ...]}; failures: failure states of failed episodes in order."""
    root.mkdir(parents=True)
    per_task = [
        {"task_group": c, "task_id": t, "metrics": {"successes": s, "video_paths": [f"videos/{t}_0.mp4"]}}
        for (c, t), s in results.items()
    ]
    (root / "eval_info.json").write_text(json.dumps({"per_task": per_task, "overall": {}}))
    (root / "videos").mkdir()
    for _, t in results:
        (root / "videos" / f"{t}_0.mp4").write_bytes(b"")
    (root / "episodes").mkdir()
    fails = iter(failures)
    lines = []
    for (c, t), succ in results.items():
        for k, s in enumerate(succ):
            # the torso target steps by 2 deg at both chunk boundaries (t = 16, 32)
            targets = [[float(np.radians(2.0 * (t >= 16) + 2.0 * (t >= 32))), 1.0] for t in range(40)]
            lines.append(
                json.dumps(
                    {
                        "task": t,
                        "category": c,
                        "split": split,
                        "episode": k,
                        "success": s,
                        "failure_state": "" if s else next(fails),
                        "view_targets": targets,
                    }
                )
            )
    (root / "episodes" / "log.jsonl").write_text("\n".join(lines))
    return root


def test_chunk_jump_is_the_per_joint_median_boundary_jump_in_degrees():
    v = np.zeros((49, 2))
    v[16:, 0] = np.radians(3.0)  # torso: 3 deg at t=16, none at t=32 or t=48
    assert chunk_jump_deg(v) == pytest.approx((0.0, 0.0))
    v[32:, 1] += np.radians(5.0)  # head: 5 deg at t=32 only
    v[48:, 0] += np.radians(4.0)  # torso: 3, 0, 4 -> median 3
    assert chunk_jump_deg(v) == pytest.approx((3.0, 0.0))
    v[48:, 1] += np.radians(1.0)  # head: 0, 5, 1 -> median 1
    assert chunk_jump_deg(v) == pytest.approx((3.0, 1.0))
    assert all(np.isnan(chunk_jump_deg(v[:10])))  # shorter than one chunk


def test_chunk_jump_is_the_mean_over_episodes_of_the_episode_medians():
    a = np.zeros((33, 2))
    a[16:, 0] = np.radians(2.0)  # medians: torso 2 (one boundary at 16; 32 has no jump -> median 1)
    b = np.zeros((33, 2))
    b[16:, 0] = np.radians(6.0)
    b[32:, 0] += np.radians(6.0)  # torso 6, 6 -> median 6
    short = np.zeros((5, 2))  # no boundary: left out of the mean
    torso, head = mean_chunk_jump(
        [{"view_targets": a.tolist()}, {"view_targets": b.tolist()}, {"view_targets": short.tolist()}]
    )
    assert torso == pytest.approx((1.0 + 6.0) / 2) and head == pytest.approx(0.0)


def test_report_tables_match_hand_computed_values(tmp_path):
    res_id = {
        ("SS", "click_bell_rotate_view"): [True, True, False, True],
        ("MD", "count_target_press_button"): [True, False, False, False],
    }
    res_ood = {
        ("SS", "click_bell_rotate_view"): [True, False, False, False],
        ("MD", "count_target_press_button"): [False, False, False, False],
    }
    a = _run(tmp_path / "a", "id", res_id, ["DM", "CO", "DM", "CR"])
    b = _run(tmp_path / "b", "ood", res_ood, ["DM"] * 3 + ["CO"] * 4)
    main([f"oracle={a}", f"oracle={b}", "--out", str(tmp_path / "rep")])
    rows = (tmp_path / "rep" / "leaderboard.csv").read_text().splitlines()
    header, row = rows[0].split(","), rows[1].split(",")
    got = dict(zip(header, row, strict=True))
    assert float(got["SS ID"]) == 75.0 and float(got["MD ID"]) == 25.0 and float(got["Avg ID"]) == 50.0
    assert float(got["SS OOD"]) == 25.0 and float(got["Avg OOD"]) == 12.5 and got["ML ID"] == ""
    fails = (tmp_path / "rep" / "failures.csv").read_text().splitlines()
    id_row = dict(zip(fails[0].split(","), fails[1].split(","), strict=True))
    assert id_row["failures"] == "4" and float(id_row["DM %"]) == 50.0 and float(id_row["CR %"]) == 25.0
    assert float(id_row["torso chunk jump (deg)"]) == pytest.approx(2.0)
    assert float(id_row["head chunk jump (deg)"]) == pytest.approx(0.0)
    per_task = (tmp_path / "rep" / "per_task.csv").read_text().splitlines()
    assert per_task[0] == "category,task,oracle ID,oracle OOD"
    assert (
        per_task[1] == "SS,click_bell_rotate_view,75.0,25.0"
        and per_task[2] == "MD,count_target_press_button,25.0,0.0"
    )
    md = (tmp_path / "rep" / "report.md").read_text()
    assert "| oracle |" in md and "leaderboard.png" in md and "click_bell_rotate_view_0.mp4" in md
    # video links are relative to the report folder (it can be moved or published with the runs)
    links = re.findall(r"\]\(([^)]+\.mp4)\)", md)
    assert len(links) == 4 and all(not link.startswith("/") for link in links)
    assert all((tmp_path / "rep" / link).is_file() for link in links)
    assert (tmp_path / "rep" / "leaderboard.png").stat().st_size > 1000
    assert (tmp_path / "rep" / "per_task.png").stat().st_size > 1000


def test_runs_of_one_label_and_split_make_one_row(tmp_path):
    """A policy trained per task and evaluated per task: one run folder per task, one leaderboard row."""
    bell = _run(
        tmp_path / "bell", "id", {("SS", "click_bell_rotate_view"): [True, True, False, True]}, ["DM"]
    )
    count = _run(tmp_path / "count", "id", {("MD", "count_target_press_button"): [False] * 4}, ["CO"] * 4)
    main([f"act={bell}", f"act={count}", "--out", str(tmp_path / "rep")])
    rows = (tmp_path / "rep" / "leaderboard.csv").read_text().splitlines()
    assert len(rows) == 2
    got = dict(zip(rows[0].split(","), rows[1].split(","), strict=True))
    assert float(got["SS ID"]) == 75.0 and float(got["MD ID"]) == 0.0 and float(got["Avg ID"]) == 37.5
    fails = (tmp_path / "rep" / "failures.csv").read_text().splitlines()
    row = dict(zip(fails[0].split(","), fails[1].split(","), strict=True))
    assert row["failures"] == "5" and float(row["DM %"]) == 20.0 and float(row["CO %"]) == 80.0
    with pytest.raises(ValueError, match="click_bell_rotate_view in both"):
        main([f"act={bell}", f"act={bell}", "--out", str(tmp_path / "rep2")])


def test_report_needs_a_split_it_can_tell(tmp_path):
    a = _run(tmp_path / "a", "id", {("SS", "click_bell_rotate_view"): [True]}, [])
    for f in (a / "episodes").glob("*"):
        f.unlink()
    with pytest.raises(ValueError, match="cannot tell the split"):
        main([str(a), "--out", str(tmp_path / "rep")])
    main([f"oracle:id={a}", "--out", str(tmp_path / "rep")])
    assert "oracle" in (tmp_path / "rep" / "leaderboard.csv").read_text()


def _write_video(path, colour, n=20):
    """A real H.264 clip (LeRobot's writer, as lerobot-eval uses): grey frames, the last one ``colour``."""
    from lerobot.utils.io_utils import write_video

    frames = [np.full((48, 64, 3), 90, np.uint8) for _ in range(n - 1)] + [
        np.full((48, 64, 3), colour, np.uint8)
    ]
    write_video(path, frames, fps=15)


def test_report_html_is_self_contained_and_renders_in_a_headless_browser(tmp_path):
    import base64
    import io
    import shutil

    from helpers.headless_browser import open_page
    from PIL import Image

    res = {
        ("SS", "click_bell_rotate_view"): [True, False],
        ("MD", "count_target_press_button"): [False, True],
    }
    a = _run(tmp_path / "a", "id", res, ["DM", "CO"])
    b = _run(tmp_path / "b", "ood", res, ["CR", "DM"])
    clips = sorted([*(a / "videos").glob("*.mp4"), *(b / "videos").glob("*.mp4")])
    for k, clip in enumerate(clips):
        _write_video(clip, (200, 30, 30) if k < 2 else (30, 30, 200))
    # a budget for the first three clips in the report's order (run a, then b): the fourth is linked
    order = sorted((a / "videos").glob("*.mp4")) + sorted((b / "videos").glob("*.mp4"))
    budget_mb = (sum(c.stat().st_size for c in order[:3]) + 1) / 2**20
    rep = tmp_path / "rep"
    main([f"oracle={a}", f"oracle={b}", "--out", str(rep), "--inline-video-mb", str(budget_mb)])
    page = (rep / "report.html").read_text()
    assert page.count('src="data:video/mp4;base64,') == 3 and page.count('src="data:image/png;base64,') == 2
    assert "3 videos embedded, 1 linked" in page
    # the poster is the clip's last frame (where the episode ended)
    poster = re.search(r'poster="data:image/jpeg;base64,([^"]+)"', page).group(1)
    rgb = np.asarray(Image.open(io.BytesIO(base64.b64decode(poster))).convert("RGB"), float).mean((0, 1))
    assert rgb[0] > 150 and rgb[2] < 80

    state = open_page(rep / "report.html", screenshot=tmp_path / "shot.png")
    assert state["title"] == "ActiveArena leaderboard" and state["table_rows"] == [1, 2, 2]
    assert len(state["images"]) == 2 and all(ok and w > 500 for ok, w, _ in state["images"])
    assert len(state["videos"]) == 4 and all(r >= 2 and w == 64 and h == 48 for r, w, h, _ in state["videos"])
    assert state["external"] == [os.path.relpath(order[3], rep)]  # the linked clip, relative to the report
    shot = np.asarray(Image.open(tmp_path / "shot.png").convert("RGB"), float)
    assert shot.shape[1] == 1280 and shot.std() > 10  # something was drawn

    # self-contained: the page alone, away from its PNGs and runs, still shows tables, charts, videos
    alone = tmp_path / "elsewhere" / "deeper" / "report.html"
    alone.parent.mkdir(parents=True)
    shutil.copy(rep / "report.html", alone)
    state = open_page(alone)
    assert all(ok and w > 500 for ok, w, _ in state["images"])
    assert sum(r >= 2 and w == 64 for r, w, _, _ in state["videos"]) == 3  # the linked one is not here


def test_exported_records_rebuild_the_same_table_without_videos(tmp_path):
    """--export-records copies what a committed table needs (run.json, policy config, eval_info,
    episode logs) and nothing else; the table built from the copies equals the original's."""
    run = tmp_path / "runs" / "act_bell"
    _run(run / "id", "id", {("SS", "click_bell_rotate_view"): [True, False, True]}, ["CR"])
    (run / "policy").mkdir()
    (run / "policy" / "config.json").write_text('{"type": "act"}')
    (run / "run.json").write_text(json.dumps({"label": "act", "splits": ["id"]}))
    (run / "checkpoint.safetensors").write_bytes(b"weights")
    main([str(run), "--out", str(tmp_path / "rep"), "--export-records", str(tmp_path / "records")])
    copy = tmp_path / "records" / "act_bell"
    files = sorted(str(f.relative_to(copy)) for f in copy.rglob("*") if f.is_file())
    assert files == ["id/episodes/log.jsonl.gz", "id/eval_info.json", "policy/config.json", "run.json"]
    packed = (copy / "id/episodes/log.jsonl.gz").read_bytes()
    assert gzip.decompress(packed) == (run / "id/episodes/log.jsonl").read_bytes()
    assert "video_paths" not in (copy / "id" / "eval_info.json").read_text()
    main([str(copy), "--out", str(tmp_path / "rep2")])
    for table in ("leaderboard.csv", "failures.csv", "per_task.csv"):
        assert (tmp_path / "rep2" / table).read_text() == (tmp_path / "rep" / table).read_text()
    with pytest.raises(FileExistsError, match="remove it to export"):
        main([str(run), "--out", str(tmp_path / "rep3"), "--export-records", str(tmp_path / "records")])
    with pytest.raises(ValueError, match="no run.json"):
        main([str(run / "id"), "--out", str(tmp_path / "rep4"), "--export-records", str(tmp_path / "r2")])
