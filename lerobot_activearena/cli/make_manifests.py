"""`activearena-make-manifests`: regenerate the evaluation seed manifests with a simulator-only run
of the scripted expert, and report any difference from the shipped ones.

For each task and split, candidate seeds from ``EVAL_SEED_START`` upwards are tried in order; a seed
enters the manifest when its scene samples validly and the expert solves it. Rejected seeds are kept
in the file with their reasons.
"""

from __future__ import annotations

import argparse
import json
import os
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from tqdm import tqdm

from ..envs.manifests import EVAL_SEED_START, MANIFEST_DIR, MANIFEST_SIZE
from ..tasks import task_names


def _check(job):
    task, split, seed = job
    from ..episodes.rollout import run_expert_episode

    try:
        r = run_expert_episode(task, seed, split)
        return seed, r.success, r.failure, r.length
    except Exception as exc:  # sampling failures count as invalid seeds
        return seed, False, f"{type(exc).__name__}: {exc}"[:200], 0


def build_split(task: str, split: str, size: int, pool: ProcessPoolExecutor, bar: tqdm) -> dict:
    seeds, rejected, lengths = [], {}, []
    nxt = EVAL_SEED_START
    while len(seeds) < size:
        batch = [(task, split, s) for s in range(nxt, nxt + size - len(seeds))]
        nxt += len(batch)
        for seed, ok, failure, length in pool.map(_check, batch):
            if ok and len(seeds) < size:
                seeds.append(seed)
                lengths.append(length)
            elif not ok:
                rejected[str(seed)] = failure
            bar.update()
        if nxt - EVAL_SEED_START > 20 * size:
            raise RuntimeError(
                f"{task}/{split}: fewer than {size} solvable seeds in {nxt - EVAL_SEED_START} candidates"
            )
    return {"seeds": seeds, "rejected": rejected, "expert_mean_frames": round(sum(lengths) / len(lengths), 1)}


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--tasks", default="all", help="task name, category, 'all', or a comma list")
    p.add_argument("--splits", default="id,ood")
    p.add_argument("--size", type=int, default=MANIFEST_SIZE)
    p.add_argument("--out", type=Path, default=MANIFEST_DIR, help="manifest folder (default: the package's)")
    p.add_argument("--workers", type=int, default=os.cpu_count())
    p.add_argument("--check", action="store_true", help="only report differences; do not write")
    args = p.parse_args(argv)
    os.environ.setdefault("MUJOCO_GL", "egl")
    tasks = task_names(args.tasks)
    splits = [s.strip() for s in args.splits.split(",") if s.strip()]
    args.out.mkdir(parents=True, exist_ok=True)
    differences = 0
    with ProcessPoolExecutor(args.workers) as pool, tqdm(desc="manifest episodes", unit="ep") as bar:
        for task in tasks:
            path = args.out / f"{task}.json"
            old = json.loads(path.read_text()) if path.exists() else None
            new = {"task": task, "seed_start": EVAL_SEED_START, "splits": {}}
            for split in splits:
                new["splits"][split] = build_split(task, split, args.size, pool, bar)
                if old is not None and split in old.get("splits", {}):
                    was, now = old["splits"][split]["seeds"], new["splits"][split]["seeds"]
                    if was != now:
                        differences += 1
                        changed = sorted(set(was) ^ set(now))
                        print(
                            f"{task}/{split}: manifest differs ({len(changed)} seeds changed, e.g. {changed[:5]})"
                        )
                    else:
                        print(f"{task}/{split}: unchanged ({len(now)} seeds)")
                else:
                    print(
                        f"{task}/{split}: new manifest ({len(new['splits'][split]['seeds'])} seeds, "
                        f"{len(new['splits'][split]['rejected'])} rejected)"
                    )
            if old is not None:  # keep other splits already in the file
                for split, entry in old.get("splits", {}).items():
                    new["splits"].setdefault(split, entry)
            if not args.check:
                path.write_text(json.dumps(new, indent=1) + "\n")
    print(
        f"{differences} manifest(s) differ from the previous ones"
        + (" (not written: --check)" if args.check else "")
    )
    if args.check and differences:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
