"""`activearena-build-dataset`: run the scripted expert and write the episodes it solves as a
LeRobotDataset v3 (head video, state, action, instruction, every per-frame annotation, keyframe
flags), sharded through datatrove (local processes or Slurm) and merged with LeRobot's aggregation.
Re-running the same command resumes an interrupted build."""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path

from ..datasets_build.features import MAX_OBJECTS
from ..datasets_build.pipeline import build_dataset
from ..datasets_build.plan import BuildPlan
from .args import int_ranges


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repo-id", required=True, help="e.g. your-hf-user/activearena_bench_id")
    p.add_argument(
        "--root", type=Path, required=True, help="local dataset folder (written when the build completes)"
    )
    p.add_argument(
        "--tasks", default="all", help="task name, category (SS/SL/ML/MD/IA), 'all', or a comma list"
    )
    p.add_argument("--split", default="id", choices=["id", "ood"])
    g = p.add_mutually_exclusive_group()
    g.add_argument(
        "--episodes", type=int, help="kept (solved) episodes per task (default 100, the paper's ID set)"
    )
    g.add_argument(
        "--seeds",
        type=int_ranges,
        help="explicit scene seeds, e.g. 0-9,42 (failures are skipped and recorded)",
    )
    p.add_argument("--seed-start", type=int, default=0, help="first seed with --episodes (default 0)")
    p.add_argument(
        "--episodes-per-shard", type=int, default=10, help="episodes per shard (the unit of resume)"
    )
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: all cores)")
    p.add_argument("--executor", default="local", choices=["local", "slurm"])
    p.add_argument(
        "--slurm",
        type=json.loads,
        default=None,
        help='Slurm options for datatrove\'s SlurmPipelineExecutor as JSON, e.g. \'{"partition": "cpu", "time": "04:00:00"}\'',
    )
    p.add_argument("--work-dir", type=Path, default=None, help="shards and logs (default: <root>.work)")
    p.add_argument("--keep-shards", action="store_true", help="keep the per-shard datasets after merging")
    p.add_argument("--overwrite", action="store_true", help="replace an existing --root / unfinished build")
    p.add_argument(
        "--push-to-hub", action="store_true", help="upload with LeRobotDataset.push_to_hub when done"
    )
    p.add_argument("--private", action="store_true")
    args = p.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    if args.executor == "slurm" and not args.slurm:
        p.error('--executor slurm needs --slurm \'{"partition": ..., "time": ...}\'')
    try:
        plan = BuildPlan(
            repo_id=args.repo_id,
            split=args.split,
            tasks=[args.tasks],
            episodes=(100 if args.episodes is None else args.episodes) if args.seeds is None else None,
            seeds=args.seeds,
            seed_start=args.seed_start,
            episodes_per_shard=args.episodes_per_shard,
            max_objects=MAX_OBJECTS,
        )
    except ValueError as exc:
        p.error(str(exc))
    summary = build_dataset(
        plan,
        args.root,
        work_dir=args.work_dir,
        workers=args.workers,
        executor=args.executor,
        slurm=args.slurm,
        overwrite=args.overwrite,
        keep_shards=args.keep_shards,
        push_to_hub=args.push_to_hub,
        private=args.private,
    )
    if summary is None:
        print(f"submitted to Slurm; the merge job writes {args.root}")
        return
    print(
        f"{args.root}: {summary['episodes']} episodes, {summary['frames']} frames, {summary['skipped']} skipped seeds"
        + (f", shortfall {summary['shortfall']}" if summary["shortfall"] else "")
    )


if __name__ == "__main__":
    main()
