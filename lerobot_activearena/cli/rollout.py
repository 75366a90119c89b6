"""`activearena-rollout`: a scripted rollout of the reference scene (scan with the torso, then
pick and shake a can) that writes an annotated MP4 and per-frame annotations.

Until the task suite lands this is the project's end-to-end smoke job: physics, control,
rendering, visibility and annotation in one run.
"""

from __future__ import annotations

import argparse
import json
import logging
import time
from pathlib import Path

import numpy as np
from tqdm import tqdm

from ..expert.ik import ArmIK
from ..expert.motion import interpolate_joints
from ..expert.pick import pick_and_shake
from ..sim import action as A
from ..sim.scene import CONTROL_HZ, reference_scene
from ..sim.simulator import ActiveArenaSim
from ..sim.video import Mp4Writer, draw_annotations

TARGET = "target_can"


def scripted_actions(sim: ActiveArenaSim, ik: ArmIK):
    """Scan left and right with the torso, return to centre, then pick and shake the target."""
    a = sim.home_action()
    for goal in (1.0, -1.0, 0.0):
        start = a.copy()
        end = a.copy()
        end[A.TORSO_YAW] = goal
        for step in interpolate_joints(start, end, max_vel=1.0):
            a = step
            yield "scan", a
    yield from pick_and_shake(sim, ik, TARGET, "right")


def frame_record(sim: ActiveArenaSim, t: int, phase: str, action: np.ndarray, discovered: np.ndarray) -> dict:
    vis = sim.visibility()
    discovered |= vis.visible
    cam = sim.head_camera()
    eef = sim.end_effector_poses()
    state = sim.state()
    return {
        "frame_index": t,
        "timestamp": t / CONTROL_HZ,
        "phase": phase,
        "state": state.tolist(),
        "action": action.tolist(),
        "clipped_action": sim.last_clip.as_dict() if sim.last_clip is not None and sim.last_clip.any else {},
        "waist_heading_deg": float(90.0 + np.degrees(state[A.TORSO_YAW])),
        "visible_object_mask": vis.visible.astype(int).tolist(),
        "visible_fraction": np.round(vis.visible_fraction, 4).tolist(),
        "discovered_object_mask": discovered.astype(int).tolist(),
        "object_uv_norm": np.round(vis.uv_norm, 4).tolist(),
        "intrinsic_cv": cam["intrinsic_cv"].tolist(),
        "extrinsic_cv": cam["extrinsic_cv"].tolist(),
        "cam2world_gl": cam["cam2world_gl"].tolist(),
        "left_endpose": eef["left"].tolist(),
        "right_endpose": eef["right"].tolist(),
    }


def run(out: Path, seed: int, n_objects: int) -> dict:
    out.mkdir(parents=True, exist_ok=True)
    model, info = reference_scene(seed, n_objects=n_objects, target=TARGET).compile()
    sim = ActiveArenaSim(model, info)
    names = [o.name for o in info.objects]
    discovered = np.zeros(len(names), bool)
    ik = ArmIK()
    t0 = time.perf_counter()
    frames = 0
    target_body = sim.data.body(TARGET)
    z0 = float(target_body.xpos[2])
    with Mp4Writer(out / "head.mp4", fps=CONTROL_HZ) as video, open(out / "annotations.jsonl", "w") as ann:
        bar = tqdm(desc="rollout", unit="frame")
        for phase, action in scripted_actions(sim, ik):
            rec = frame_record(sim, frames, phase, action, discovered)
            ann.write(json.dumps(rec) + "\n")
            rgb = sim.render_head()
            visible = [(uv[0], uv[1], n) for n, uv, v in zip(names, rec["object_uv_norm"], rec["visible_object_mask"]) if v]
            lines = [f"t={frames:3d}  phase={phase}  torso={np.degrees(rec['state'][A.TORSO_YAW]):+.0f}deg  "
                     f"head={np.degrees(rec['state'][A.HEAD_PITCH]):+.0f}deg",
                     f"visible {sum(rec['visible_object_mask'])}/{len(names)}  discovered {int(discovered.sum())}"]
            video.write(draw_annotations(rgb, lines, visible))
            sim.step(action)
            frames += 1
            bar.update()
        bar.close()
    elapsed = time.perf_counter() - t0
    lifted = float(target_body.xpos[2]) - z0
    summary = {
        "seed": seed,
        "frames": frames,
        "seconds": round(elapsed, 2),
        "annotated_frames_per_s": round(frames / elapsed, 1),
        "target_lift_m": round(lifted, 4),
        "discovered": [n for n, d in zip(names, discovered) if d],
        "objects": [{"index": i, "name": o.name, "category": o.category} for i, o in enumerate(info.objects)],
        "video": "head.mp4",
        "annotations": "annotations.jsonl",
    }
    (out / "episode.json").write_text(json.dumps(summary, indent=2))
    sim.close()
    return summary


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", type=Path, default=Path("outputs/rollout"), help="output folder")
    p.add_argument("--seed", type=int, default=0, help="scene seed")
    p.add_argument("--n-objects", type=int, default=24, help="clutter objects besides the target can")
    args = p.parse_args(argv)
    logging.basicConfig(level=logging.WARNING)
    s = run(args.out, args.seed, args.n_objects)
    print(f"wrote {args.out / s['video']} and {args.out / s['annotations']} ({s['frames']} frames, "
          f"{s['annotated_frames_per_s']} frames/s incl. video); target lifted {s['target_lift_m'] * 100:.1f} cm; "
          f"discovered {len(s['discovered'])}/{len(s['objects'])} objects")


if __name__ == "__main__":
    main()
