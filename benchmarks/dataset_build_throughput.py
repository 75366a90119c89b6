"""Dataset-builder throughput: expert episodes per hour per core, render + annotation + keyframes +
streaming AV1 encoding + parquet + LeRobot aggregation included.

    python benchmarks/dataset_build_throughput.py --tasks all --episodes 4            # all cores
    taskset -c 0 python benchmarks/dataset_build_throughput.py --tasks all --episodes 4   # one core

Runs the real ``build_dataset`` (the code behind ``activearena-build-dataset``) into a temporary
root and prints episodes/hour/core, frames/episode, and the ratio to the paper-scale target
(35 tasks x 100 ID episodes, ~581k frames, on one 2-core machine in < 8 h: >= 220 episodes/hour/core
at ~166 frames per episode). Per-frame time is also reported, since our episodes are shorter or
longer than the paper's 166 frames on average.

It then projects the wall time of a release recipe (``--recipe``, default the paper's training set
``datasets_build/train_id.json``) here and on a 64-core node. Assumptions, printed with the figures:
each task's episodes are as long as in this sample; every core of the node builds shards at this
run's per-core rate (one worker per core, as here); an expert failure costs one more episode; the
merge is serial and grows linearly with the episode count (timed here by merging the shards again).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import tempfile
import time
from pathlib import Path

from lerobot_activearena.datasets_build.merge import merge_shards
from lerobot_activearena.datasets_build.pipeline import build_dataset
from lerobot_activearena.datasets_build.plan import BuildPlan
from lerobot_activearena.datasets_build.recipe import load_recipe
from lerobot_activearena.tasks import task_names

RECIPE = Path(__file__).parents[1] / "datasets_build" / "train_id.json"

TARGET_EPS_PER_HOUR_CORE = 220
PAPER_FRAMES_PER_EPISODE = 166


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--tasks", default="all")
    p.add_argument("--episodes", type=int, default=2, help="kept episodes per task")
    p.add_argument("--split", default="id")
    p.add_argument(
        "--workers",
        type=int,
        default=len(os.sched_getaffinity(0)),
        help="worker processes (default: all cores)",
    )
    p.add_argument("--recipe", type=Path, default=RECIPE, help="the release whose wall time is projected")
    p.add_argument("--node-cores", type=int, default=64)
    args = p.parse_args()
    plan = BuildPlan(
        repo_id="bench/throughput",
        split=args.split,
        tasks=args.tasks.split(","),
        episodes=args.episodes,
        episodes_per_shard=args.episodes,
    )
    tmp = Path(tempfile.mkdtemp(prefix="aa_build_"))
    try:
        t0 = time.perf_counter()
        summary = build_dataset(plan, tmp / "ds", workers=args.workers, progress=False, keep_shards=True)
        wall = time.perf_counter() - t0
        episodes = [
            json.loads(line) for line in (tmp / "ds/meta/activearena/episodes.jsonl").read_text().splitlines()
        ]
        t0 = time.perf_counter()
        merge_shards(plan, tmp / "ds.work", tmp / "ds2")
        merge_s = time.perf_counter() - t0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    n, frames = summary["episodes"], summary["frames"]
    expert_s = sum(e["seconds"] for e in episodes)  # expert + render + annotation only
    # Renderer (llvmpipe) and AV1 encoder threads spread over every core the process may use, so the
    # honest denominator is the cores available (pin with `taskset -c 0` for a one-core figure).
    cores = len(os.sched_getaffinity(0))
    eph_core = 3600 * n / wall / cores
    s_per_frame = wall * cores / frames
    at_paper_length = 3600 / (s_per_frame * PAPER_FRAMES_PER_EPISODE)
    print(
        f"tasks {len(plan.tasks)}, kept episodes {n} (skipped {summary['skipped']}), frames {frames} "
        f"({frames / n:.0f}/episode), workers {args.workers}, cores available {cores}, wall {wall:.1f} s"
    )
    print(
        f"expert + render + annotation: {expert_s:.1f} s ({frames / expert_s:.0f} frames/s per core); "
        f"encoding + writing + merge: the remaining {wall * cores - expert_s:.1f} core-s"
    )
    print(
        f"episodes/hour/core: {eph_core:.0f} at {frames / n:.0f} frames/episode; "
        f"{at_paper_length:.0f} at the paper's {PAPER_FRAMES_PER_EPISODE} frames/episode "
        f"(target {TARGET_EPS_PER_HOUR_CORE}: ratio {at_paper_length / TARGET_EPS_PER_HOUR_CORE:.2f})"
    )
    hours = 35 * 100 * PAPER_FRAMES_PER_EPISODE * s_per_frame / 2 / 3600  # core-seconds over 2 cores
    print(
        f"paper-scale ID set (3500 episodes x {PAPER_FRAMES_PER_EPISODE} frames) on 2 cores: ~{hours:.1f} h"
    )
    project(args, episodes, summary, wall - merge_s, cores, merge_s)


def project(args, episodes: list[dict], summary: dict, shard_wall: float, cores: int, merge_s: float) -> None:
    """Projected wall time of ``args.recipe`` from this sample (assumptions in the module doc)."""
    recipe = load_recipe(args.recipe)
    tasks = task_names(recipe["tasks"])
    per_task = recipe["episodes"] or len(recipe["seeds"])
    frames_of = {}
    for e in episodes:
        frames_of.setdefault(e["task"], []).append(e["length"])
    missing = [t for t in tasks if t not in frames_of]
    if missing:
        print(f"cannot project {args.recipe.name}: no sample of {missing} (run with --tasks all)")
        return
    core_s_per_frame = shard_wall * cores / summary["frames"]
    failure = summary["skipped"] / (summary["episodes"] + summary["skipped"])
    frames = sum(per_task * sum(frames_of[t]) / len(frames_of[t]) for t in tasks)
    core_s = frames * core_s_per_frame * (1 + failure)
    merge = merge_s * len(tasks) * per_task / summary["episodes"]
    shard_s = (
        recipe["episodes_per_shard"] * max(sum(v) / len(v) for v in frames_of.values()) * core_s_per_frame
    )
    print(
        f"recipe {args.recipe.name}: {len(tasks)} tasks x {per_task} episodes, ~{frames / 1e3:.0f}k frames, "
        f"{core_s / 3600:.1f} core-hours (at {core_s_per_frame * 1e3:.0f} core-ms/frame, failure rate "
        f"{failure:.1%}) + a serial merge of ~{merge / 60:.1f} min ({merge_s:.1f} s for {summary['episodes']} "
        f"episodes here)"
    )
    for n in (cores, args.node_cores):
        hours = (core_s / n + merge + shard_s) / 3600  # + one shard's time: the last shards' tail
        print(f"  projected wall time on {n} cores: {hours:.1f} h")


if __name__ == "__main__":
    main()
