"""`activearena-validity`: run the validity suite (adversarial policies that must not score, and the
expert reference row) on seeds outside the evaluation manifests, as datatrove shards (one per task,
split and adversary; local processes or ``--executor slurm``) like ``activearena-eval``; write one
record file per shard under ``--out/records/`` (re-run to resume), ``validity.md`` and
``validity.csv``, and print the table.

    activearena-validity --tasks all --adversaries random,held_random,still,blind_replay,fixed_view_expert,expert \
        --seeds 50 --splits id --workers 2 --out outputs/validity

It is a measurement: the exit code is 0 whether or not the targets are met (bad arguments exit 2).
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

from ..validity.adversaries import ADVERSARIES, VALIDITY_SEED_BASE
from ..validity.suite import RECORDS, missed, run_suite, summarise, write_report


def _list(text: str) -> list[str]:
    return [s.strip() for s in text.split(",") if s.strip()]


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--tasks", default="all", help="task name, category, 'all', or a comma list")
    p.add_argument(
        "--adversaries", default=",".join(ADVERSARIES), help=f"comma list of {', '.join(ADVERSARIES)}"
    )
    p.add_argument("--seeds", type=int, default=50, help="episodes per task, split and adversary")
    p.add_argument("--seed-base", type=int, default=VALIDITY_SEED_BASE, help="first scene seed")
    p.add_argument("--splits", default="id", help="comma list of id, ood")
    p.add_argument("--workers", type=int, default=os.cpu_count())
    p.add_argument("--out", type=Path, default=Path("outputs/validity"))
    p.add_argument("--executor", default="local", choices=["local", "slurm"])
    p.add_argument(
        "--slurm",
        type=json.loads,
        default=None,
        help='datatrove SlurmPipelineExecutor options as JSON, e.g. \'{"partition": "cpu", "time": "04:00:00"}\'',
    )
    args = p.parse_args(argv)
    if args.executor == "slurm" and not args.slurm:
        p.error('--executor slurm needs --slurm \'{"partition": ..., "time": ...}\'')
    os.environ.setdefault("MUJOCO_GL", "egl")
    from ..tasks import task_names
    from ..tasks.base import SPLITS

    adversaries, splits = _list(args.adversaries), _list(args.splits)
    bad = [a for a in adversaries if a not in ADVERSARIES] or ([] if adversaries else ["(none)"])
    if bad:
        p.error(f"unknown adversary {', '.join(bad)}; valid adversaries: {', '.join(ADVERSARIES)}")
    bad = [s for s in splits if s not in SPLITS] or ([] if splits else ["(none)"])
    if bad:
        p.error(f"unknown split {', '.join(bad)}; valid splits: {', '.join(SPLITS)}")
    if args.seeds < 1:
        p.error("--seeds must be at least 1")
    try:
        tasks = task_names(args.tasks)
    except ValueError as exc:
        p.error(str(exc))
    seeds = range(args.seed_base, args.seed_base + args.seeds)
    try:
        records = run_suite(
            tasks,
            adversaries,
            seeds,
            splits,
            args.out,
            args.workers,
            executor=args.executor,
            slurm=args.slurm,
        )
    except ValueError as exc:  # seeds that collide with a manifest
        p.error(str(exc))
    if records is None:
        print(f"submitted to Slurm; the report job writes {args.out}/validity.md")
        return
    rows = summarise(records)
    print("\n" + write_report(rows, args.out))
    print(
        f"\nwrote {args.out}/validity.md, validity.csv ({len(records)} episodes under {args.out}/{RECORDS}/)"
    )
    miss = missed(rows)
    print(f"targets missed: {'; '.join(miss)}" if miss else "all targets met")


if __name__ == "__main__":
    main()
