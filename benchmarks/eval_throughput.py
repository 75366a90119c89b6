"""Evaluation throughput of the oracle policy: `activearena-eval` with 1 and 2 shard workers (and,
for reference, one plain `lerobot-eval` process), in episodes/hour of wall time including start-up.

    python benchmarks/eval_throughput.py --tasks SS,MD,IA --episodes 4 --workers 1,2

The oracle reads no pixels, so `--pixels false` (the default, as in the protocol run) skips the
head-camera render of each observation; `--pixels true` renders it as a learned policy would need.
Rollout videos are off. The full protocol's wall time is measured by running it (docs/eval.md).
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def _exe(name: str) -> str:
    return shutil.which(name, path=str(Path(sys.executable).parent)) or name


def run_activearena_eval(tasks: str, episodes: int, workers: int, pixels: bool, splits: str) -> dict:
    out = Path(tempfile.mkdtemp(prefix="aa_eval_")) / "run"
    cmd = [
        _exe("activearena-eval"),
        "--policy.type=activearena_expert",
        "--policy.device=cpu",
        f"--env.render_pixels={'true' if pixels else 'false'}",
        f"--tasks={tasks}",
        f"--splits={splits}",
        f"--episodes={episodes}",
        f"--workers={workers}",
        "--videos=0",
        f"--out={out}",
    ]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise SystemExit(p.stderr[-3000:])
    n = succ = 0
    for split in splits.split(","):
        o = json.loads((out / split / "eval_info.json").read_text())["overall"]
        n += o["n_episodes"]
        succ += o["pc_success"] * o["n_episodes"] / 100
    shutil.rmtree(out.parent, ignore_errors=True)
    return {"episodes": n, "success": 100 * succ / n, "wall_s": wall}


def run_lerobot_eval(tasks: str, episodes: int, pixels: bool, split: str) -> dict:
    out = Path(tempfile.mkdtemp(prefix="aa_eval_")) / "eval"
    cmd = [
        _exe("lerobot-eval"),
        "--policy.type=activearena_expert",
        "--env.type=activearena",
        f"--env.task={tasks}",
        f"--env.split={split}",
        "--env.expert_channel=true",
        f"--env.render_pixels={'true' if pixels else 'false'}",
        f"--eval.n_episodes={episodes}",
        "--eval.batch_size=1",
        "--policy.device=cpu",
        f"--output_dir={out}",
    ]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise SystemExit(p.stderr[-3000:])
    o = json.loads((out / "eval_info.json").read_text())["overall"]
    shutil.rmtree(out.parent, ignore_errors=True)
    return {"episodes": o["n_episodes"], "success": o["pc_success"], "wall_s": wall}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--tasks", default="SS,MD,IA")
    p.add_argument("--episodes", type=int, default=4, help="episodes per task and split")
    p.add_argument("--splits", default="id")
    p.add_argument("--workers", default="1,2")
    p.add_argument("--pixels", choices=["true", "false", "both"], default="false")
    p.add_argument(
        "--lerobot-eval", action="store_true", help="also time one plain lerobot-eval process (first split)"
    )
    args = p.parse_args()
    pix = {"true": [True], "false": [False], "both": [False, True]}[args.pixels]
    print("| runner | head images | episodes | success % | wall s | episodes/hour |")
    print("|---|---|---|---|---|---|")
    for pixels in pix:
        rows = []
        if args.lerobot_eval:
            rows.append(
                (
                    "lerobot-eval, 1 process",
                    run_lerobot_eval(args.tasks, args.episodes, pixels, args.splits.split(",")[0]),
                )
            )
        for w in [int(x) for x in args.workers.split(",")]:
            rows.append(
                (
                    f"activearena-eval, {w} worker{'s' if w > 1 else ''}",
                    run_activearena_eval(args.tasks, args.episodes, w, pixels, args.splits),
                )
            )
        for name, r in rows:
            print(
                f"| {name} | {'rendered' if pixels else 'not rendered'} | {r['episodes']} | {r['success']:.0f} | "
                f"{r['wall_s']:.0f} | {3600 * r['episodes'] / r['wall_s']:.0f} |",
                flush=True,
            )


if __name__ == "__main__":
    main()
