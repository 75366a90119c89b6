"""`activearena-expert-video` writes an annotated MP4, per-frame JSONL and the sidecar."""

import json
import subprocess
import sys

import av

from lerobot_activearena.cli.expert_video import main as expert_video_main


def test_expert_video_cli_writes_video_annotations_and_sidecar(tmp_path):
    expert_video_main(["--task", "SS", "--seed", "1", "--out", str(tmp_path)])
    ep = tmp_path / "click_bell_rotate_view_id_1"
    side = json.loads((ep / "episode.json").read_text())
    assert side["success"] and side["task"] == "click_bell_rotate_view"
    assert {"instruction", "objects", "subtasks", "transitions", "final_discovered"} <= set(side)
    # one-level task: the three lower search sectors at the home pitch (headings 90, 36, 144 deg)
    assert [v["heading_deg"] for v in side["search_views"]] == [90.0, 35.57, 144.43]
    assert {v["head_pitch"] for v in side["search_views"]} == {1.0}
    lines = (ep / "annotations.jsonl").read_text().splitlines()
    assert len(lines) == side["frames"]
    first = json.loads(lines[0])
    assert first["frame_index"] == 0 and len(first["action"]) == 18 and "visible_object_mask" in first
    with av.open(str(ep / "head.mp4")) as c:
        frames = [f.to_ndarray(format="rgb24") for f in c.decode(video=0)]
    assert len(frames) == side["frames"] and frames[0].shape == (384, 512, 3)
    assert frames[0][:30].mean() < 60, "the annotation banner is drawn at the top"


def test_expert_video_cli_lists_tasks():
    out = subprocess.run(
        [sys.executable, "-m", "lerobot_activearena.cli.expert_video", "--list"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0 and "check_block_color" in out.stdout and " IA " in out.stdout
