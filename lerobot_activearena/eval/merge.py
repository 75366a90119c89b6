"""Merge a run's episode records into lerobot-eval's output layout, one folder per split
(``<split>/eval_info.json`` with per_task / per_group / overall, ``<split>/episodes/records.jsonl``),
and write the run's leaderboard report."""

from __future__ import annotations

import json
from collections import defaultdict
from pathlib import Path

import numpy as np

from .protocol import EvalPlan
from .report import build_report
from .shard import read_records, video_path


def _aggregate(successes: list[bool]) -> dict:
    s = [float(x) for x in successes]
    mean = float(np.mean(s)) if s else float("nan")
    return {"avg_sum_reward": mean, "avg_max_reward": mean, "pc_success": 100.0 * mean, "n_episodes": len(s)}


def missing_episodes(plan: EvalPlan, run_dir: Path) -> list[tuple[str, str, int]]:
    got = read_records(Path(run_dir) / "records")
    return [(s.task, s.split, k) for s in plan.shards for k in s.episodes if (s.task, s.split, k) not in got]


def merge_run(plan: EvalPlan, run_dir: Path, report: bool = True) -> dict:
    """Write ``<split>/eval_info.json`` and the report; refuses while episodes are unfinished."""
    run_dir = Path(run_dir)
    missing = missing_episodes(plan, run_dir)
    if missing:
        ex = ", ".join(f"{t}/{s}#{k}" for t, s, k in missing[:3])
        raise RuntimeError(
            f"{len(missing)} of {plan.n_episodes} episodes are unfinished (e.g. {ex}); "
            "re-run the same activearena-eval command to resume them"
        )
    records = read_records(run_dir / "records")
    by_split: dict[str, dict] = {}
    for split in plan.splits:
        per_task, groups, overall, lines = [], defaultdict(list), [], []
        for task in plan.tasks:
            recs = [records[(task, split, k)] for k in plan.episodes]
            succ = [bool(r["success"]) for r in recs]
            videos = [
                str(p)
                for s in plan.shards
                if (s.task, s.split) == (task, split)
                for k in s.episodes
                if (p := video_path(run_dir, s, k)).exists()
            ]
            cat = plan.category(task)
            per_task.append(
                {
                    "task_group": cat,
                    "task_id": task,
                    "metrics": {
                        "sum_rewards": [float(x) for x in succ],
                        "max_rewards": [float(x) for x in succ],
                        "successes": succ,
                        "video_paths": videos,
                    },
                }
            )
            groups[cat] += succ
            overall += succ
            lines += [json.dumps(dict(r, category=cat, fixed_view=plan.fixed_view)) for r in recs]
        info = {
            "per_task": per_task,
            "per_group": {g: _aggregate(v) for g, v in groups.items()},
            "overall": _aggregate(overall),
            "activearena": {
                "label": plan.label,
                "split": split,
                "fixed_view": plan.fixed_view,
                "episodes": plan.episodes,
                "policy_type": plan.policy.get("type"),
                "policy_path": plan.policy_path,
            },
        }
        out = run_dir / split
        (out / "episodes").mkdir(parents=True, exist_ok=True)
        (out / "eval_info.json").write_text(json.dumps(info, indent=2))
        (out / "episodes" / "records.jsonl").write_text("\n".join(lines) + "\n")
        by_split[split] = info["overall"]
    if report:
        build_report([f"{plan.label}:{s}={run_dir / s}" for s in plan.splits], run_dir / "report")
    return by_split
