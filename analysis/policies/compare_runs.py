"""Episode-by-episode comparison of two `activearena-eval` runs of the same episodes (one policy
before and after a change of the scenes' look, say): successes in each, and how many episodes kept
their outcome.

    python analysis/policies/compare_runs.py docs/results/records/act_cpu_count_target_100demos \
        outputs/protocol/act_cpu_count

Reads each run's ``<split>/episodes/records.jsonl`` (or the committed ``.jsonl.gz``).
"""

from __future__ import annotations

import argparse
import gzip
import json
from pathlib import Path


def load(run: Path, split: str) -> dict[tuple[str, int], bool]:
    path = run / split / "episodes" / "records.jsonl"
    if not path.exists():
        path = path.with_suffix(".jsonl.gz")
    if not path.exists():
        raise SystemExit(
            f"{run}: no {split}/episodes/records.jsonl(.gz); is it an activearena-eval run folder?"
        )
    opener = gzip.open if path.suffix == ".gz" else open
    with opener(path, "rt") as f:
        return {(r["task"], int(r["episode"])): bool(r["success"]) for r in map(json.loads, f)}


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("before", type=Path)
    p.add_argument("after", type=Path)
    p.add_argument("--splits", default="id,ood")
    args = p.parse_args()
    for split in args.splits.split(","):
        a, b = load(args.before, split), load(args.after, split)
        if a.keys() != b.keys():
            raise SystemExit(f"{split}: the two runs played different episodes ({len(a)} vs {len(b)})")
        same = sum(a[k] == b[k] for k in a)
        print(
            f"{split}: solved {sum(a.values())} -> {sum(b.values())} of {len(a)}; "
            f"same outcome {same}/{len(a)}; solved in both {sum(a[k] and b[k] for k in a)}"
        )


if __name__ == "__main__":
    main()
