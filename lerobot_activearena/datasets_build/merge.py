"""Merge complete shards into one LeRobotDataset with LeRobot's aggregation, and write the
ActiveArena metadata (build plan, kept episodes with their seeds, skipped seeds with reasons,
one sidecar per episode) under ``meta/activearena/``."""

from __future__ import annotations

import json
import platform
import shutil
from importlib.metadata import version
from pathlib import Path

from .card import write_card
from .features import META_DIR
from .plan import BuildPlan
from .shard import SHARD_DONE, is_complete, shard_dir


def merge_shards(plan: BuildPlan, work_dir: Path, root: Path, release: dict | None = None) -> dict:
    """Aggregate into ``<root>.merging``, write ``meta/activearena/`` and the dataset card
    (``README.md``; ``release`` holds the recipe's description and the build command), and rename
    to ``root`` at the end: ``root`` only ever holds a complete dataset."""
    from lerobot.datasets.aggregate import aggregate_datasets  # only when merging: a finished build skips it

    missing = [s.name for s in plan.shards if not is_complete(shard_dir(work_dir, s))]
    if missing:
        raise RuntimeError(
            f"{len(missing)} shard(s) are not complete ({', '.join(missing[:5])}...): run the same "
            f"build command again to resume them; worker logs are in {work_dir / 'logs'}"
        )
    summaries = [json.loads((shard_dir(work_dir, s) / SHARD_DONE).read_text()) for s in plan.shards]
    used = [(s, summ) for s, summ in zip(plan.shards, summaries, strict=True) if summ["kept"]]
    if not used:
        raise RuntimeError(
            "the expert solved none of the requested episodes; nothing to write "
            f"(skipped seeds and reasons: {work_dir / 'shards'}/*/{SHARD_DONE})"
        )
    tmp = root.with_name(root.name + ".merging")
    shutil.rmtree(tmp, ignore_errors=True)
    aggregate_datasets(
        repo_ids=[f"{plan.repo_id}-{s.name}" for s, _ in used],
        aggr_repo_id=plan.repo_id,
        roots=[shard_dir(work_dir, s) for s, _ in used],
        aggr_root=tmp,
    )
    episodes, skipped = [], []
    meta = tmp / META_DIR
    (meta / "sidecars").mkdir(parents=True)
    for summ in summaries:
        skipped += summ["skipped"]
        for ep in summ["kept"]:
            index = len(episodes)
            sidecar = ep.pop("sidecar")
            episodes.append({"episode_index": index, "shard": summ["rank"], **ep})
            (meta / "sidecars" / f"episode_{index:06d}.json").write_text(json.dumps(sidecar, indent=1))
    (meta / "episodes.jsonl").write_text("".join(json.dumps(e) + "\n" for e in episodes))
    (meta / "skipped.jsonl").write_text("".join(json.dumps(s) + "\n" for s in skipped))
    shortfall = {s["task"]: s.get("shortfall", 0) for s in summaries if s.get("shortfall")}
    build = {
        "plan": plan.to_json(),
        "episodes": len(episodes),
        "frames": sum(e["length"] for e in episodes),
        "skipped": len(skipped),
        "shortfall": shortfall,
        "package_version": version("lerobot_env_activearena"),
        "lerobot_version": version("lerobot"),
        "versions": {"mujoco": version("mujoco"), "python": platform.python_version()},
        **(release or {}),
    }
    (meta / "build.json").write_text(json.dumps(build, indent=1))
    write_card(tmp)
    if root.exists():
        shutil.rmtree(root)
    tmp.rename(root)
    return build


def read_build(root: Path) -> dict | None:
    path = Path(root) / META_DIR / "build.json"
    return json.loads(path.read_text()) if path.is_file() else None
