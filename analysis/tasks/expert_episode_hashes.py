"""The sha256 of expert episodes (actions, states and every annotation), to show a refactor changes
no behaviour: run it before and after, the lines must be equal.

    python analysis/tasks/expert_episode_hashes.py --out before.json
    python analysis/tasks/expert_episode_hashes.py --compare before.json

The default set covers every task shape and workspace: one or more tasks per category, the two-level
and the fan-double workspaces, both splits, two seeds each.
"""

from __future__ import annotations

import argparse
import hashlib
import json
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

TASKS = (
    "click_bell_rotate_view",
    "place_empty_cup_rotate_view",
    "place_shoe_rotate_view",
    "stack_blocks_two_rotate_view",
    "put_block_on_upper_easy",
    "blocks_ranking_rgb_fan_double",
    "count_target_press_button",
    "check_cola_color",
    "check_block_color",
    "shake_bottle_rotate_view",
    "match_backside_two_blocks",
)


def episode_hash(job: tuple[str, int, str]) -> tuple[str, str]:
    from lerobot_activearena.episodes.rollout import run_expert_episode

    task, seed, split = job
    r = run_expert_episode(task, seed, split)
    h = hashlib.sha256(r.actions.tobytes())
    h.update(r.states.tobytes())
    for frame in r.frames:  # the annotations: arrays by name
        for key in sorted(frame):
            h.update(key.encode())
            h.update(np.ascontiguousarray(frame[key]).tobytes())
    h.update(f"{r.success}|{r.failure}|{r.length}".encode())
    return f"{task}/{split}/{seed}", h.hexdigest()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tasks", default=",".join(TASKS))
    ap.add_argument("--seeds", default="0,1")
    ap.add_argument("--splits", default="id,ood")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", type=Path, help="write the hashes as JSON")
    ap.add_argument("--compare", type=Path, help="a JSON written by --out: report every episode that differs")
    args = ap.parse_args()
    jobs = [
        (t, int(s), sp)
        for t in args.tasks.split(",")
        for sp in args.splits.split(",")
        for s in args.seeds.split(",")
    ]
    with ProcessPoolExecutor(args.workers) as pool:
        hashes = dict(pool.map(episode_hash, jobs))
    total = hashlib.sha256("".join(f"{k}={v}\n" for k, v in sorted(hashes.items())).encode()).hexdigest()
    for key, value in hashes.items():
        print(f"{key:55s} {value[:16]}")
    print(f"all {len(hashes)} episodes: {total}")
    if args.out:
        args.out.write_text(json.dumps({"episodes": hashes, "all": total}, indent=1) + "\n")
    if args.compare:
        ref = json.loads(args.compare.read_text())["episodes"]
        differ = sorted(k for k in ref.keys() | hashes.keys() if ref.get(k) != hashes.get(k))
        print(
            f"{len(differ)} of {len(ref)} episodes differ from {args.compare}"
            + "".join(f"\n  {k}" for k in differ)
        )
        raise SystemExit(1 if differ else 0)


if __name__ == "__main__":
    main()
