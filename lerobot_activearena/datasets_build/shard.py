"""Build one shard: a complete, finalized LeRobotDataset of the shard's kept episodes, plus its
sidecars and seed log. A shard directory exists only once it is complete (written under a
temporary name and renamed), so an interrupted build never leaves a half-written shard behind."""

from __future__ import annotations

import json
import logging
import os
import shutil
from pathlib import Path

from ..episodes.rollout import DemoVariation
from ..sim.embodiment import ROBOT_TYPE
from ..sim.scene import HEAD_SIZE
from ..tasks.registry import get_task
from .features import FPS, dataset_features
from .plan import ShardSpec
from .record import record_episode

log = logging.getLogger(__name__)
SHARD_DONE = "shard.json"


def shard_dir(work_dir: Path, spec: ShardSpec) -> Path:
    return work_dir / "shards" / spec.name


def is_complete(path: Path) -> bool:
    return (path / SHARD_DONE).is_file()


def build_shard(
    spec: ShardSpec,
    split: str,
    repo_id: str,
    work_dir: Path,
    max_objects: int,
    encoder_threads: int | None = 1,
    progress: Path | None = None,
    image_size: tuple[int, int] = HEAD_SIZE,
    variation: DemoVariation = DemoVariation(),
) -> dict:
    """Record the shard's episodes; returns (and stores) its summary. Safe to call again: a complete
    shard is returned as is, leftovers of an interrupted attempt are removed first."""
    import datasets  # LeRobot and torch load in the workers that record, not in the CLI that plans
    from lerobot.datasets.lerobot_dataset import LeRobotDataset

    final = shard_dir(work_dir, spec)
    datasets.disable_progress_bars()  # the shard's own per-episode bookkeeping; the build shows its own bars
    logging.getLogger("lerobot.utils.import_utils").setLevel(logging.ERROR)  # decoder probe: we only encode
    # The AV1 encoder (SVT-AV1) prints ~19 info lines per episode straight to stderr; errors only
    # (SVT_LOG=3 brings them back).
    os.environ.setdefault("SVT_LOG", "1")
    if is_complete(final):
        return json.loads((final / SHARD_DONE).read_text())
    tmp = final.with_name(final.name + ".partial")
    shutil.rmtree(tmp, ignore_errors=True)
    shutil.rmtree(final, ignore_errors=True)
    tmp.parent.mkdir(parents=True, exist_ok=True)
    features = dataset_features(max_objects, image_size)
    # LeRobot's streaming encoder is made for live recording: a frame that waits more than 0.1 s for
    # a place in its queue is dropped (a warning only), which shifts every later frame of the video
    # against the episode's data. We add a whole episode at once, faster than real time, so the
    # queue holds a whole episode: nothing waits, nothing is dropped (save_episode drains it).
    episode_frames = get_task(spec.task).max_episode_steps + 1
    ds = LeRobotDataset.create(
        f"{repo_id}-{spec.name}",
        fps=FPS,
        features=features,
        root=tmp,
        robot_type=ROBOT_TYPE,
        use_videos=True,
        streaming_encoding=True,
        encoder_queue_maxsize=episode_frames,
        encoder_threads=encoder_threads,
        video_backend="pyav",
    )
    kept, skipped, tried = [], [], 0
    for seed in list(spec.seeds) + list(spec.reserve):
        if len(kept) == spec.quota:
            break
        tried += 1
        try:
            rec = record_episode(spec.task, seed, split, image_size, variation)
            failure = rec.result.failure
        except Exception as exc:  # e.g. no valid scene for this seed: recorded, never hidden
            rec, failure = None, f"{type(exc).__name__}: {exc}"
        if rec is None or not rec.result.success:
            skipped.append({"task": spec.task, "seed": seed, "split": split, "reason": failure})
            log.warning("skipped %s seed %d (%s): %s", spec.task, seed, split, failure)
        else:
            r = rec.result
            for row in rec.rows(features):
                ds.add_frame(row)
            ds.save_episode()
            kept.append(
                {
                    "shard_episode": len(kept),
                    "task": spec.task,
                    "seed": seed,
                    "split": split,
                    "length": r.length,
                    "seconds": round(r.seconds, 2),
                    "sidecar": r.sidecar,
                }
            )
        if progress is not None:
            progress.write_text(
                json.dumps({"tried": tried, "kept": len(kept), "frames": sum(k["length"] for k in kept)})
            )
    ds.finalize()
    summary = {
        "rank": spec.rank,
        "task": spec.task,
        "split": split,
        "quota": spec.quota,
        "tried": tried,
        "kept": kept,
        "skipped": skipped,
    }
    if len(kept) < spec.quota:
        summary["shortfall"] = spec.quota - len(kept)
    (tmp / SHARD_DONE).write_text(json.dumps(summary, indent=1))
    tmp.rename(final)
    return summary
