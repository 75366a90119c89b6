"""Run a build: one datatrove task per shard (local processes or Slurm array jobs; datatrove skips
ranks it already completed, so re-running resumes), then merge, then optionally push to the Hub."""

from __future__ import annotations

import contextlib
import json
import logging
import os
import shutil
from pathlib import Path

from datatrove.pipeline.base import PipelineStep
from tqdm import tqdm

from ..sharding import ProgressBars, one_core, run_local, submit_slurm
from .card import card_kwargs
from .merge import merge_shards, read_build
from .plan import BuildPlan
from .shard import build_shard, is_complete, shard_dir

log = logging.getLogger(__name__)


class BuildShardStep(PipelineStep):
    """datatrove step: rank r builds shard r of the plan."""

    name = "ActiveArena expert shard"
    type = "SIM"

    def __init__(self, plan: BuildPlan, work_dir: str, encoder_threads: int | None = 1):
        super().__init__()
        self.plan, self.work_dir, self.encoder_threads = plan, work_dir, encoder_threads

    def run(self, data=None, rank: int = 0, world_size: int = 1):
        spec = self.plan.shards[rank]
        if self.encoder_threads == 1:  # one worker per core
            one_core()
        work = Path(self.work_dir)
        (work / "progress").mkdir(parents=True, exist_ok=True)
        summary = build_shard(
            spec,
            self.plan.split,
            self.plan.repo_id,
            work,
            self.plan.max_objects,
            self.encoder_threads,
            progress=work / "progress" / f"{spec.name}.json",
            image_size=tuple(self.plan.image_size),
            variation=self.plan.variation,
        )
        self.stat_update("episodes_kept", value=len(summary["kept"]))
        self.stat_update("episodes_skipped", value=len(summary["skipped"]))
        return iter(())


class MergeStep(PipelineStep):
    """datatrove step (one task) that merges the shards: the Slurm job that depends on the shard jobs."""

    name = "ActiveArena merge"
    type = "MERGE"

    def __init__(self, plan: BuildPlan, work_dir: str, root: str, release: dict | None = None):
        super().__init__()
        self.plan, self.work_dir, self.root, self.release = plan, work_dir, root, release

    def run(self, data=None, rank: int = 0, world_size: int = 1):
        merge_shards(self.plan, Path(self.work_dir), Path(self.root), self.release)
        return iter(())


class _Progress(ProgressBars):
    """Episode and shard progress bars fed by the workers' progress files."""

    def __init__(self, plan: BuildPlan, work_dir: Path):
        super().__init__()
        self.plan, self.work_dir = plan, work_dir
        self.shards = tqdm(total=len(plan.shards), desc="shards", unit="shard", position=0)
        self.eps = tqdm(total=sum(s.quota for s in plan.shards), desc="episodes", unit="ep", position=1)

    def refresh(self) -> None:
        done = sum(is_complete(shard_dir(self.work_dir, s)) for s in self.plan.shards)
        kept = 0
        for s in self.plan.shards:
            p = self.work_dir / "progress" / f"{s.name}.json"
            with contextlib.suppress(OSError, ValueError):  # being rewritten
                kept += json.loads(p.read_text())["kept"] if p.is_file() else 0
        self.shards.update(done - self.shards.n)
        self.eps.update(kept - self.eps.n)

    def close(self) -> None:
        self.shards.close()
        self.eps.close()


def _prepare(plan: BuildPlan, root: Path, work_dir: Path, overwrite: bool) -> bool:
    """Returns True when ``root`` already holds this exact build."""
    built = read_build(root)
    if built is not None and built["plan"] == json.loads(json.dumps(plan.to_json())) and not overwrite:
        return True
    if root.exists() and not overwrite:
        raise FileExistsError(
            f"{root} already exists and is not this build; choose another --root or pass "
            "--overwrite to replace it"
        )
    plan_file = work_dir / "plan.json"
    if overwrite:
        shutil.rmtree(work_dir, ignore_errors=True)
    elif plan_file.is_file() and not plan.same_as(plan_file):
        raise FileExistsError(
            f"{work_dir} holds an unfinished build with different arguments; re-run it with "
            "the same arguments to resume, or pass --overwrite (or another --work-dir)"
        )
    work_dir.mkdir(parents=True, exist_ok=True)
    plan.save(plan_file)
    return False


def build_dataset(
    plan: BuildPlan,
    root: Path,
    work_dir: Path | None = None,
    workers: int | None = None,
    executor: str = "local",
    slurm: dict | None = None,
    overwrite: bool = False,
    keep_shards: bool = False,
    push_to_hub: bool = False,
    private: bool = False,
    progress: bool = True,
    recipe: dict | None = None,
    command: str | None = None,
) -> dict | None:
    """Build (or resume) the dataset at ``root``. Returns the build summary; with the Slurm executor
    the jobs are submitted and None is returned (the merge job writes ``root``). ``recipe`` (file,
    description, overridden flags) and ``command`` go into ``build.json`` and the dataset card."""
    release = {"recipe": recipe, "command": command}
    root = Path(root).resolve()
    work_dir = Path(work_dir).resolve() if work_dir else root.with_name(root.name + ".work")
    if _prepare(plan, root, work_dir, overwrite):
        log.info("%s already holds this build; nothing to do", root)
        summary = read_build(root)
    else:
        workers = max(1, min(workers or os.cpu_count() or 1, len(plan.shards)))
        threads = 1 if workers > 1 else None
        step = BuildShardStep(plan, str(work_dir), encoder_threads=threads)
        if executor == "slurm":
            submit_slurm(
                step,
                len(plan.shards),
                MergeStep(plan, str(work_dir), str(root), release),
                work_dir,
                "activearena-build",
                slurm,
            )
            return None
        if executor != "local":
            raise ValueError(f"executor must be 'local' or 'slurm', got {executor!r}")
        run_local(
            step,
            len(plan.shards),
            workers,
            work_dir / "logs",
            _Progress(plan, work_dir) if progress else None,
        )
        summary = merge_shards(plan, work_dir, root, release)
        if not keep_shards:
            shutil.rmtree(work_dir, ignore_errors=True)
    if push_to_hub:
        push(plan.repo_id, root, private=private)
    return summary


def push(repo_id: str, root: Path, private: bool = False) -> None:
    """Upload with LeRobot's own path (``LeRobotDataset.push_to_hub``), metadata folder included,
    with the build's dataset card (``card.py``) in LeRobot's card template."""
    from lerobot.datasets.lerobot_dataset import LeRobotDataset

    card = card_kwargs(root)
    card.pop("repo_id")
    ds = LeRobotDataset(repo_id, root=root, video_backend="pyav")
    ds.push_to_hub(private=private, **card)
