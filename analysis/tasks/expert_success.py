"""Expert success, episode length and speed per task and split (no rendering unless --render).

    python analysis/tasks/expert_success.py --tasks all --splits id,ood --seeds 100 --workers 2

Prints a Markdown table: success rate, mean and 95th-percentile episode length (frames, up to the
reported success) against the task's step limit (target: p95 <= 0.9 x limit), failures by reason,
expert frames/s per worker (physics + IK + visibility + annotation; + head rendering with --render).
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path


def _run(job):
    task, seed, split, render = job
    from lerobot_activearena.episodes.rollout import run_expert_episode

    cb = (lambda t, sim, frame, action: sim.render_head()) if render else None
    try:
        r = run_expert_episode(task, seed, split, on_frame=cb)
        return {
            "task": task,
            "seed": seed,
            "split": split,
            "success": r.success,
            "failure": r.failure,
            "frames": r.length,
            "seconds": r.seconds,
            "penetration": r.health["max_penetration_m"],
        }
    except Exception as exc:  # a sampler or framework error is a failure to report, not a crash
        return {
            "task": task,
            "seed": seed,
            "split": split,
            "success": False,
            "failure": f"error: {exc!r}"[:200],
            "frames": 0,
            "seconds": 0.0,
            "penetration": 0.0,
        }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--tasks", default="all")
    p.add_argument("--splits", default="id,ood")
    p.add_argument("--seeds", type=int, default=100)
    p.add_argument("--first-seed", type=int, default=0)
    p.add_argument("--workers", type=int, default=os.cpu_count())
    p.add_argument("--render", action="store_true", help="also render the head camera every frame")
    p.add_argument("--json", type=Path, default=None, help="write per-episode results here")
    args = p.parse_args()
    os.environ.setdefault("MUJOCO_GL", "egl")
    from lerobot_activearena.tasks import task_names

    jobs = [
        (t, s, sp, args.render)
        for t in task_names(args.tasks)
        for sp in args.splits.split(",")
        for s in range(args.first_seed, args.first_seed + args.seeds)
    ]
    t0 = time.perf_counter()
    from tqdm import tqdm

    with ProcessPoolExecutor(args.workers) as pool:
        results = list(tqdm(pool.map(_run, jobs, chunksize=1), total=len(jobs), desc="expert episodes"))
    wall = time.perf_counter() - t0
    if args.json:
        args.json.write_text(json.dumps(results, indent=1))
    groups = collections.defaultdict(list)
    for r in results:
        groups[(r["task"], r["split"])].append(r)
    import numpy as np

    from lerobot_activearena.tasks import get_task

    print(
        "\n| task | split | success | mean frames | p95 frames | limit | p95 / limit | max penetration (mm) "
        "| frames/s/worker | failures |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for (task, split), rs in groups.items():
        ok = sum(r["success"] for r in rs)
        frames = [r["frames"] for r in rs if r["frames"]]
        solved = [r["frames"] for r in rs if r["success"]] or [0]
        limit = get_task(task).max_episode_steps
        p95 = float(np.percentile(solved, 95))
        fps = sum(frames) / max(1e-9, sum(r["seconds"] for r in rs))
        reasons = collections.Counter((r["failure"] or "")[:70] for r in rs if not r["success"])
        print(
            f"| {task} | {split} | {ok}/{len(rs)} ({100 * ok / len(rs):.0f}%) | {np.mean(solved):.0f} | {p95:.0f} | "
            f"{limit} | {p95 / limit:.2f} | {1000 * max(r['penetration'] for r in rs):.1f} | {fps:.0f} | "
            + "; ".join(f"{n}x {k}" for k, n in reasons.most_common(3))
            + " |"
        )
    n = len(results)
    print(f"\n{n} episodes in {wall:.0f} s with {args.workers} workers: {3600 * n / wall:.0f} episodes/hour")


if __name__ == "__main__":
    main()
