"""Does the policy take the search's decision at a chunk boundary? Stay with the side it faces, or turn
across, as the demonstration did, predicted from the training samples themselves.

    python analysis/policies/chunk_decision.py --repo-id local/cpu_click_bell_200_p16 \\
        --root outputs/datasets/cpu_click_bell_200_p16_vla --episodes 0-39 --at 16 CHECKPOINT...

At frame ``--at`` of each training episode the demonstration either turns its torso across (more than
0.5 rad within the next 16 frames: the bell is not on this side) or stays (it centres the bell it
sees). The chunk predicted from the dataset sample of that frame (history from the delta timestamps,
as in training) is classified the same way. Printed per checkpoint: the right decisions among the
episodes that stay and among those that turn. A policy that always turns scores all of one and none
of the other; one that reads the bell from the image scores both. With ``--probe``, also whether the
demonstration's decision is linearly readable from the policy's last-layer states at the action
queries (``decision_probe.py``'s logistic regression, cross-validated over the episodes; the
majority class is the floor): whether what the head lacks is in the features at all.

``--record FILE.jsonl`` appends each checkpoint's figures there and skips checkpoints it already holds
(an interrupted sweep goes on where it stopped); ``--plot FILE.png`` draws every run in the record:
the right decisions against the training step.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
from pathlib import Path

import numpy as np

from lerobot_activearena.cli.args import int_ranges
from lerobot_activearena.sim.action import TORSO_YAW


def _sibling(name: str):
    """Another script of this folder, as a module (the folder is not a package)."""
    spec = importlib.util.spec_from_file_location(name, Path(__file__).with_name(f"{name}.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


training_scenes, decision_probe = _sibling("training_scenes"), _sibling("decision_probe")

TURN = 0.5  # rad of torso yaw within a chunk: a turn across to the other side


def turns(chunk: np.ndarray) -> bool:
    """Whether a chunk of actions turns the torso across (its yaw range exceeds ``TURN``)."""
    yaw = chunk[:, TORSO_YAW]
    return bool(yaw.max() - yaw.min() > TURN)


def decisions(scenes, episodes: list[int], at: int) -> list[tuple[int, bool, bool]]:
    """(episode, the demonstration turns, the predicted chunk turns) at frame ``at`` of each episode
    that has a full chunk after it."""
    out = []
    for ep in episodes:
        frames = scenes.frames(ep)
        if len(frames) < at + 16:
            continue
        recorded = np.stack([scenes.ds.hf_dataset[frames[at + k]]["action"].numpy() for k in range(16)])
        out.append((ep, turns(recorded), turns(scenes.dataset_chunk(frames[at]))))
    return out


def checkpoint_key(ckpt: Path) -> tuple[str, int]:
    """(run folder name, training step) of a ``RUN/checkpoints/STEP/pretrained_model`` folder."""
    ckpt = ckpt.resolve()
    if ckpt.parent.parent.name != "checkpoints" or not ckpt.parent.name.isdigit():
        raise SystemExit(f"{ckpt}: not a RUN/checkpoints/<step>/pretrained_model folder")
    return ckpt.parents[2].name, int(ckpt.parent.name)


def read_record(path: Path | None) -> list[dict]:
    if path is None or not path.exists():
        return []
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def plot(rows: list[dict], out: Path) -> None:
    """Per run, the share of right decisions among the stays and among the turns, by training step."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.8))
    for i, run in enumerate(dict.fromkeys(r["run"] for r in rows)):
        mine = sorted((r for r in rows if r["run"] == run), key=lambda r: r["step"])
        steps = [r["step"] for r in mine]
        colour = f"C{i}"
        ax.plot(
            steps, [r["stays_right"] / r["stays"] for r in mine], "-o", color=colour, label=f"{run}: stays"
        )
        ax.plot(
            steps, [r["turns_right"] / r["turns"] for r in mine], "--s", color=colour, label=f"{run}: turns"
        )
    ax.set_xlabel("training step")
    ax.set_ylabel("right decisions at the chunk boundary")
    ax.set_ylim(-0.03, 1.03)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=2)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("checkpoints", type=Path, nargs="*", help="pretrained_model folders")
    p.add_argument("--repo-id")
    p.add_argument("--root", type=Path, help="the dataset the checkpoints were trained on")
    p.add_argument("--episodes", default="0-39", help="dataset episode indices, e.g. 0-39")
    p.add_argument("--at", type=int, default=16, help="the chunk boundary (default 16)")
    p.add_argument("--probe", action="store_true", help="also a linear probe of the decision")
    p.add_argument("--record", type=Path, help="append each checkpoint's figures to this .jsonl")
    p.add_argument("--plot", type=Path, help="draw the record's runs to this .png")
    args = p.parse_args()
    if args.plot and not args.record:
        p.error("--plot draws the --record file; pass --record FILE.jsonl")
    if args.checkpoints and not (args.repo_id and args.root):
        p.error("checkpoints are scored on their training dataset: pass --repo-id and --root")
    if not (args.checkpoints or args.plot):
        p.error("pass checkpoints to score, or --record FILE --plot FILE.png to draw a record")
    done = {(r["run"], r["step"], r["at"], r["episodes"]) for r in read_record(args.record)}
    head = "| checkpoint | demonstration stays: policy stays | demonstration turns: policy turns |"
    if args.checkpoints:
        print(head + (" linear probe (majority class) |" if args.probe else ""))
        print("|---|---|---|" + ("---|" if args.probe else ""))
    for ckpt in args.checkpoints:
        run, step = checkpoint_key(ckpt) if args.record else ("", 0)
        if args.record and (run, step, args.at, args.episodes) in done:
            print(f"| {run}/{step} | in {args.record} |")
            continue
        scenes = training_scenes.TrainingScenes(ckpt, args.repo_id, args.root)
        rows = decisions(scenes, int_ranges(args.episodes), args.at)
        stay = [pred for _, rec, pred in rows if not rec]
        turn = [pred for _, rec, pred in rows if rec]
        name = "/".join(ckpt.parts[-4:-1]) if len(ckpt.parts) >= 4 else str(ckpt)
        line = f"| {name} | {stay.count(False)} of {len(stay)} | {turn.count(True)} of {len(turn)} |"
        if args.probe:
            y = np.array([rec for _, rec, _ in rows])
            indices = [scenes.frames(ep)[args.at] for ep, _, _ in rows]
            x, _, _ = decision_probe.features(ckpt, args.repo_id, args.root, indices)
            line += f" {decision_probe.best_probe(x, y)} ({max(y.mean(), 1 - y.mean()):.0%}) |"
        print(line, flush=True)
        if args.record:
            row = {"run": run, "step": step, "at": args.at, "episodes": args.episodes}
            row.update(
                stays_right=stay.count(False), stays=len(stay), turns_right=turn.count(True), turns=len(turn)
            )
            with args.record.open("a") as f:
                f.write(json.dumps(row) + "\n")
    if args.plot:
        plot(read_record(args.record), args.plot)


if __name__ == "__main__":
    os.environ.setdefault("MUJOCO_GL", "egl")
    main()
