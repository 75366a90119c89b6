"""`activearena-expert-video`: run the scripted expert on one task episode and write an MP4 with
the annotations drawn on it (stage, subtask, visible objects, target point), plus the per-frame
annotations (JSONL) and the episode sidecar (JSON)."""

from __future__ import annotations

import argparse
import json
import logging
import math
from pathlib import Path

import numpy as np
from tqdm import tqdm

from ..annotations.schema import CAMERA_MODE_NAMES, STAGE_NAMES
from ..episodes.rollout import run_expert_episode
from ..sim.scene import CONTROL_HZ
from ..sim.video import Mp4Writer, draw_annotations
from ..tasks import get_task, task_names


def _jsonable(frame: dict) -> dict:
    return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in frame.items()}


def render_episode(task: str, seed: int, split: str, out: Path) -> dict:
    out.mkdir(parents=True, exist_ok=True)
    spec = get_task(task)
    bar = tqdm(desc=f"{task} seed {seed} ({split})", unit="frame", total=spec.max_episode_steps)
    with Mp4Writer(out / "head.mp4", fps=CONTROL_HZ) as video, open(out / "annotations.jsonl", "w") as ann:
        labels: list[str] = []

        def on_frame(t, sim, frame, action):
            if not labels:
                labels.extend(o.name for o in sim.info.objects)
            sub = spec.subtask(int(frame["subtask"]))
            theta = float(frame["camera_target_theta"])
            lines = [
                f"t={t:3d}  T{sub.id} {sub.name}  stage={STAGE_NAMES[int(frame['stage'])]}",
                f"camera={CAMERA_MODE_NAMES[int(frame['camera_mode'])]}  heading={float(frame['waist_heading_deg']):.0f}deg"
                + ("" if math.isnan(theta) else f" -> {theta:.0f}deg")
                + f"  info_complete={int(frame['info_complete'])}",
                "visible: "
                + ", ".join(n for n, v in zip(labels, frame["visible_object_mask"], strict=True) if v),
            ]
            pts = []
            uv = frame["target_uv_norm"]
            if uv[0] >= 0:
                f = int(frame["focus_object_idx"])
                pts.append((float(uv[0]), float(uv[1]), f"target: {labels[f]}"))
            video.write(draw_annotations(sim.render_head(), lines, pts))
            rec = _jsonable(frame)
            rec.update(frame_index=t, action=np.asarray(action).round(5).tolist())
            ann.write(json.dumps(rec) + "\n")
            bar.update()

        result = run_expert_episode(task, seed, split, on_frame=on_frame)
    bar.close()
    side = dict(
        result.sidecar,
        frames=result.length,
        seconds=round(result.seconds, 2),
        frames_per_s=round(result.length / max(result.seconds, 1e-9), 1),
        health=result.health,
    )
    (out / "episode.json").write_text(json.dumps(side, indent=2))
    return side


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument(
        "--task",
        default="all",
        help="task name, category (SS/SL/ML/MD/IA), 'all', or a comma list (default: all)",
    )
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--split", choices=("id", "ood"), default="id")
    p.add_argument(
        "--out",
        type=Path,
        default=Path("outputs/expert"),
        help="output root; each episode goes to <out>/<task>_<split>_<seed>/",
    )
    p.add_argument("--list", action="store_true", help="list the registered tasks and exit")
    args = p.parse_args(argv)
    logging.basicConfig(level=logging.WARNING)
    if args.list:
        for name in task_names("all"):
            t = get_task(name)
            print(f"{name:40s} {t.category}  {t.instruction}")
        return
    failed = 0
    for name in task_names(args.task):
        out = args.out / f"{name}_{args.split}_{args.seed}"
        s = render_episode(name, args.seed, args.split, out)
        failed += not s["success"]
        status = "success" if s["success"] else f"FAILED ({s['failure']})"
        print(
            f"{name} seed {args.seed} ({args.split}): {status}; {s['frames']} frames at {s['frames_per_s']} "
            f"frames/s incl. rendering and video; wrote {out}/head.mp4, annotations.jsonl, episode.json"
        )
    if failed:
        raise SystemExit(f"{failed} expert episode(s) failed")


if __name__ == "__main__":
    main()
