"""`activearena-learning-curve`: for every checkpoint of a lerobot-train run, the open-loop action
error on held-out episodes and the closed-loop success on the first ID manifest episodes of a task
(with ``--validation``: on the manifest's episodes after the protocol's 50, to choose a checkpoint
without touching the protocol's); writes ``curve.jsonl`` (one record per checkpoint: success and the
failed episodes' DM / CO / CR counts; resumable) and ``learning_curve.png``.

    activearena-learning-curve outputs/train/act_cpu_click_bell --task click_bell_rotate_view \\
        --heldout-repo-id local/cpu_click_bell_heldout --heldout-root outputs/datasets/cpu_click_bell_heldout \\
        --episodes 20 --out outputs/curves/act_cpu_click_bell

With ``--overlay LABEL=CURVE_DIR ...`` it measures nothing: it draws the curves those runs wrote on one
axis (a chunk-12 run beside its memory-free partner) into the PNG ``--out`` names.

    activearena-learning-curve --overlay chunk-12=outputs/curves/a memory-free=outputs/curves/b \\
        --title "click_bell_rotate_view" --out outputs/curves/pair.png
"""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path


def closed_loop_success(policy_dir: Path, task: str, episodes: int, out: Path, first: int = 0) -> dict:
    """activearena-eval on ``episodes`` ID manifest episodes from index ``first``, at the
    checkpoint's image size; resumes an interrupted run."""
    from ..episodes.episode import FAILURE_STATES
    from ..eval.learning_curve import image_size
    from ..eval.shard import read_records
    from .eval import main as activearena_eval

    h, w = image_size(policy_dir)
    activearena_eval(
        [
            f"--policy.path={policy_dir}",
            "--policy.device=cpu",
            f"--env.observation_height={h}",
            f"--env.observation_width={w}",
            f"--tasks={task}",
            "--splits=id",
            f"--episode-indices={first}-{first + episodes - 1}",
            "--videos=0",
            f"--out={out}",
        ]
    )
    info = json.loads((out / "id" / "eval_info.json").read_text())
    failed = [r["failure_state"] for r in read_records(out / "records").values() if not r["success"]]
    return {
        "episodes": info["overall"]["n_episodes"],
        "success": info["overall"]["pc_success"],
        "indices": f"{first}-{first + episodes - 1}",
        "failures": {state: failed.count(state) for state in FAILURE_STATES},
    }


def learning_curve(
    train_dir: Path,
    task: str,
    out: Path,
    heldout: tuple[str, Path] | None = None,
    episodes: int = 20,
    every: int = 1,
    validation: bool = False,
) -> list[dict]:
    """One record per checkpoint (every ``every``-th, always the last): ``{"step", "open_loop",
    "closed_loop"}``, written to ``out/curve.jsonl`` as each is done; finished ones are kept.
    ``validation``: the closed-loop episodes start after the protocol's (manifest index 50)."""
    from tqdm import tqdm

    from ..envs.manifests import MANIFEST_SIZE, PROTOCOL_EPISODES
    from ..eval.learning_curve import checkpoints, open_loop_error

    first = PROTOCOL_EPISODES if validation else 0
    if first + episodes > MANIFEST_SIZE:
        raise ValueError(
            f"{episodes} episodes from manifest index {first} pass the manifest's {MANIFEST_SIZE}; "
            f"use --episodes <= {MANIFEST_SIZE - first}"
        )
    indices = f"{first}-{first + episodes - 1}"

    out.mkdir(parents=True, exist_ok=True)
    records_file = out / "curve.jsonl"
    done = {}
    if records_file.is_file():
        for line in records_file.read_text().splitlines():
            rec = json.loads(line)
            had = rec["closed_loop"].get("indices", f"0-{rec['closed_loop']['episodes'] - 1}")
            if had != indices:
                raise ValueError(
                    f"{records_file} holds closed-loop results on manifest episodes {had}, not {indices}; "
                    "use another --out (or the same --episodes / --validation as before)"
                )
            done[rec["step"]] = rec
    ckpts = checkpoints(train_dir)
    ckpts = [c for k, c in enumerate(ckpts) if k % every == every - 1 or k == len(ckpts) - 1]
    for step, model in tqdm(ckpts, desc="checkpoints", unit="ckpt"):
        if step in done:
            continue
        rec: dict = {"step": step, "task": task}
        if heldout is not None:
            rec["open_loop"] = open_loop_error(model, heldout[0], heldout[1])
        rec["closed_loop"] = closed_loop_success(model, task, episodes, out / f"eval_{step:06d}", first)
        done[step] = rec
        with records_file.open("a") as f:
            f.write(json.dumps(rec) + "\n")
    return [done[s] for s in sorted(done)]


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("train_dir", type=Path, nargs="?", help="a lerobot-train --output_dir (with checkpoints/)")
    p.add_argument("--task", help="the task the closed-loop episodes play (required with train_dir)")
    p.add_argument(
        "--overlay",
        nargs="+",
        metavar="LABEL=CURVE_DIR",
        help="draw the curves earlier runs wrote on one axis instead of measuring; --out is then a .png",
    )
    p.add_argument(
        "--episodes", type=int, default=20, help="ID manifest episodes per checkpoint (default 20)"
    )
    p.add_argument("--every", type=int, default=1, help="every k-th checkpoint (the last always)")
    p.add_argument(
        "--validation",
        action="store_true",
        help="closed loop on the manifest's ID episodes after the protocol's 50 (to choose a checkpoint)",
    )
    p.add_argument("--heldout-repo-id", default=None, help="a dataset the policy was not trained on")
    p.add_argument("--heldout-root", type=Path, default=None)
    p.add_argument("--out", type=Path, required=True)
    p.add_argument("--title", default=None)
    args = p.parse_args(argv)
    if args.overlay:
        if args.train_dir is not None:
            p.error("--overlay draws curves already measured: give it without train_dir")
        return _overlay(p, args)
    if args.train_dir is None or args.task is None:
        p.error("give a train_dir and --task to measure a curve (or --overlay to draw measured ones)")
    if args.episodes < 1 or args.every < 1:
        p.error("--episodes and --every must be >= 1")
    if (args.heldout_repo_id is None) != (args.heldout_root is None):
        p.error("give both --heldout-repo-id and --heldout-root, or neither")
    logging.basicConfig(level=logging.WARNING)
    from ..eval.learning_curve import best_checkpoint, plot_curve
    from ..tasks import get_task

    try:
        get_task(args.task)
        heldout = (args.heldout_repo_id, args.heldout_root) if args.heldout_root else None
        records = learning_curve(
            args.train_dir, args.task, args.out, heldout, args.episodes, args.every, args.validation
        )
    except (FileNotFoundError, KeyError, ValueError) as exc:
        p.error(str(exc))
    plot_curve(
        records, args.out / "learning_curve.png", args.title or f"{args.train_dir.name} on {args.task}"
    )
    for r in records:
        ol, failures = r.get("open_loop", {}), r["closed_loop"].get("failures")
        print(
            f"step {r['step']:>6}: ID success {r['closed_loop']['success']:5.1f}% "
            f"({r['closed_loop']['episodes']} episodes)"
            + (", failures " + " / ".join(f"{k} {v}" for k, v in failures.items()) if failures else "")
            + (f", held-out |error| {ol['l1']:.4f} (view {ol['l1_view']:.4f})" if ol else "")
        )
    best = best_checkpoint(records)
    where = "validation" if args.validation else "ID"
    indices = best["closed_loop"].get("indices", f"0-{best['closed_loop']['episodes'] - 1}")
    print(f"best on {where} episodes {indices}: step {best['step']} ({best['closed_loop']['success']:.1f}%)")
    print(f"wrote {args.out}/curve.jsonl and {args.out}/learning_curve.png")


def _overlay(p: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    from ..eval.learning_curve import best_checkpoint, plot_overlay, read_curve

    if args.out.suffix != ".png":
        p.error(f"--out {args.out}: with --overlay, name the .png to write")
    curves = []
    for item in args.overlay:
        label, sep, folder = item.partition("=")
        if not sep or not label or not folder:
            p.error(
                f"--overlay {item!r}: write each curve as LABEL=CURVE_DIR, e.g. chunk-12=outputs/curves/a"
            )
        try:
            curves.append((label, read_curve(Path(folder))))
        except (FileNotFoundError, ValueError) as exc:
            p.error(str(exc))
    plot_overlay(curves, args.out, args.title or ", ".join(label for label, _ in curves))
    for label, records in curves:
        best = best_checkpoint(records)
        print(
            f"{label}: {len(records)} checkpoints, best step {best['step']} ({best['closed_loop']['success']:.1f}%)"
        )
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
