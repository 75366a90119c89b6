"""Outcomes of `activearena-eval` runs by one of the scenes' drawn parameters (the count of the
count tasks, say): per value, how many episodes, successes and failure states. Several runs of
different episodes of one policy pool into one table (a protocol run and its validation runs).

    python analysis/policies/outcomes_by_scene.py --param count --splits id \
        docs/results/records/small_oft_action_12_wos_count_target_left_200demos_p16_192_b64 \
        outputs/val/wos_chunk12_1500_50-99

Each episode's scene is drawn again from its ``scene_seed`` (the same seed gives the same scene), so
the table needs only the records: ``<split>/episodes/records.jsonl(.gz)`` or a run's ``records/``.
"""

from __future__ import annotations

import argparse
import gzip
import json
from collections import Counter, defaultdict
from pathlib import Path


def read_episodes(run: Path, split: str) -> list[dict]:
    """A run's finished episodes of ``split``: the merged records, else the shards' raw ones."""
    merged = run / split / "episodes" / "records.jsonl"
    for path in (merged, merged.with_suffix(".jsonl.gz")):
        if path.exists():
            with (gzip.open if path.suffix == ".gz" else open)(path, "rt") as f:
                return [json.loads(line) for line in f if line.strip()]
    from lerobot_activearena.eval.shard import read_records

    raw = [r for (_, s, _), r in read_records(run / "records").items() if s == split]
    if not raw:
        raise SystemExit(f"{run}: no {split} records; is it an activearena-eval run folder?")
    return raw


def tabulate(episodes: list[dict], value_of) -> dict:
    """{value: {"episodes": n, "success": n, "failures": Counter(state)}} with ``value_of(record)``
    the parameter's value in that episode's scene; an episode played twice (two runs) counts once."""
    seen, table = set(), defaultdict(lambda: {"episodes": 0, "success": 0, "failures": Counter()})
    for r in episodes:
        key = (r["task"], r["split"], int(r["episode"]))
        if key in seen:
            continue
        seen.add(key)
        row = table[value_of(r)]
        row["episodes"] += 1
        row["success"] += bool(r["success"])
        if not r["success"]:
            row["failures"][r["failure_state"] or "?"] += 1
    return dict(table)


def scene_param(name: str):
    from lerobot_activearena.tasks import get_task
    from lerobot_activearena.tasks.sampling import sample_scene

    def value_of(record: dict):
        scene = sample_scene(get_task(record["task"]), int(record["scene_seed"]), record["split"])
        if name not in scene.params:
            raise SystemExit(
                f"{record['task']} scenes have no parameter {name!r}; they have {sorted(scene.params)}"
            )
        return scene.params[name]

    return value_of


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", type=Path, help="activearena-eval run folders (or committed records)")
    p.add_argument("--param", required=True, help="a key of the task's scene params, e.g. count")
    p.add_argument("--splits", default="id,ood")
    args = p.parse_args()
    value_of = scene_param(args.param)
    for split in args.splits.split(","):
        episodes = [r for run in args.runs for r in read_episodes(run, split)]
        table = tabulate(episodes, value_of)
        print(f"{split}: {sum(r['episodes'] for r in table.values())} episodes by {args.param}")
        print(f"  {args.param:>8}  episodes  solved  failures")
        for value in sorted(table):
            row = table[value]
            fails = ", ".join(f"{k} {n}" for k, n in sorted(row["failures"].items()))
            print(f"  {value!s:>8}  {row['episodes']:8d}  {row['success']:6d}  {fails}")


if __name__ == "__main__":
    main()
