"""The full validity table: every adversary on every task, 50 seeds outside the evaluation manifests
(id split; --ood adds the ood split), no rendering.

    python analysis/tasks/validity.py --workers 2 --out outputs/validity_bench [--ood]

Prints the Markdown table of ``lerobot_activearena.validity.suite`` (also written to
``<out>/validity.md`` / ``.csv``) and the throughput of the episodes this call ran: episodes/hour
over all workers, and seconds per episode per adversary. Resumable: a re-run with the same --out
only runs the missing episodes.
"""

from __future__ import annotations

import argparse
import collections
import os
import time
from pathlib import Path


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--tasks", default="all")
    p.add_argument("--seeds", type=int, default=50)
    p.add_argument("--ood", action="store_true", help="also run the ood split")
    p.add_argument("--workers", type=int, default=os.cpu_count())
    p.add_argument("--out", type=Path, default=Path("outputs/validity_bench"))
    args = p.parse_args()
    os.environ.setdefault("MUJOCO_GL", "egl")
    from lerobot_activearena.tasks import task_names
    from lerobot_activearena.validity.adversaries import ADVERSARIES
    from lerobot_activearena.validity.suite import (
        load_all_records,
        missed,
        run_suite,
        summarise,
        write_report,
    )

    before = set(load_all_records(args.out))
    splits = ("id", "ood") if args.ood else ("id",)
    t0 = time.perf_counter()
    records = run_suite(task_names(args.tasks), list(ADVERSARIES), args.seeds, splits, args.out, args.workers)
    wall = time.perf_counter() - t0
    rows = summarise(records)
    print("\n" + write_report(rows, args.out))
    new = [
        r
        for r in records
        if (r["task"], r["split"], r["adversary"], r["seed"]) not in before and not r.get("error")
    ]
    per_adv = collections.defaultdict(list)
    for r in new:
        per_adv[r["adversary"]].append(r["seconds"])
    print("\n| adversary | episodes run | s/episode (one worker) |\n|---|---|---|")
    for a, s in per_adv.items():
        print(f"| {a} | {len(s)} | {sum(s) / len(s):.2f} |")
    if new:
        print(
            f"\n{len(new)} episodes in {wall:.0f} s with {args.workers} workers: {3600 * len(new) / wall:.0f} episodes/hour"
        )
    miss = missed(rows)
    print(f"targets missed: {'; '.join(miss)}" if miss else "all targets met")


if __name__ == "__main__":
    main()
