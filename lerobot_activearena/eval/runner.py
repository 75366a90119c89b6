"""Run an evaluation plan as datatrove tasks (one per shard; local processes or Slurm array jobs with a
dependent merge job). Datatrove skips shards it completed; a shard killed half way replays only its
unfinished episodes, so re-running the same command resumes."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from datatrove.pipeline.base import PipelineStep
from tqdm import tqdm

from ..sharding import ProgressBars, one_core, run_local, submit_slurm
from .merge import merge_run
from .protocol import RUN_FILE, EvalPlan
from .shard import forget_loaded_policy, read_records, records_dir, run_shard


class EvalShardStep(PipelineStep):
    """datatrove step: rank r evaluates shard r of the plan."""

    name = "ActiveArena eval shard"
    type = "EVAL"

    def __init__(
        self,
        plan: EvalPlan,
        run_dir: str,
        batch_size: int,
        use_async_envs: bool,
        videos: int,
        one_thread: bool,
    ):
        super().__init__()
        self.plan, self.run_dir = plan, run_dir
        self.batch_size, self.use_async_envs, self.videos, self.one_thread = (
            batch_size,
            use_async_envs,
            videos,
            one_thread,
        )

    def run(self, data=None, rank: int = 0, world_size: int = 1):
        if self.one_thread:  # one worker per core
            one_core()
        out = run_shard(
            self.plan,
            self.plan.shards[rank],
            Path(self.run_dir),
            self.batch_size,
            self.use_async_envs,
            self.videos,
        )
        self.stat_update("episodes_run", value=out["ran"])
        return iter(())


class MergeStep(PipelineStep):
    """datatrove step (one task): the merge, as the Slurm job that depends on the shard jobs."""

    name = "ActiveArena eval merge"
    type = "MERGE"

    def __init__(self, plan: EvalPlan, run_dir: str):
        super().__init__()
        self.plan, self.run_dir = plan, run_dir

    def run(self, data=None, rank: int = 0, world_size: int = 1):
        merge_run(self.plan, Path(self.run_dir))
        return iter(())


class _Progress(ProgressBars):
    """An overall bar and one bar per running shard, fed by the shards' episode records."""

    def __init__(self, plan: EvalPlan, run_dir: Path):
        super().__init__()
        self.plan, self.run_dir = plan, run_dir
        self.total = tqdm(total=plan.n_episodes, desc="episodes", unit="ep", position=0)
        self.bars: dict[str, tqdm] = {}
        self.finished: set[str] = set()

    def refresh(self) -> None:
        n = 0
        for shard in self.plan.shards:
            if shard.name in self.finished:
                n += len(shard.episodes)
                continue
            done = min(len(shard.episodes), _count_lines(records_dir(self.run_dir, shard)))
            n += done
            if done == len(shard.episodes):
                self.finished.add(shard.name)
                if shard.name in self.bars:
                    self.bars.pop(shard.name).close()
            elif done and shard.name not in self.bars:
                self.bars[shard.name] = tqdm(
                    total=len(shard.episodes),
                    desc=shard.name,
                    unit="ep",
                    leave=False,
                    position=1 + len(self.bars),
                )
            if shard.name in self.bars:
                self.bars[shard.name].update(done - self.bars[shard.name].n)
        self.total.update(n - self.total.n)

    def close(self) -> None:
        for b in self.bars.values():
            b.close()
        self.total.close()


def _count_lines(folder: Path) -> int:
    """Finished episodes of a shard, cheaply (the progress bars do not parse the records)."""
    return sum(f.read_bytes().count(b"\n") for f in folder.glob("*.jsonl")) if folder.is_dir() else 0


def prepare_run(plan: EvalPlan, run_dir: Path, policy_config: dict, overwrite: bool = False) -> bool:
    """Create or check the run folder. Returns True when it resumes an earlier run of this plan;
    refuses a folder that holds another configuration."""
    run_file = run_dir / RUN_FILE
    if overwrite:
        shutil.rmtree(run_dir, ignore_errors=True)
    elif run_file.is_file():
        diff = plan.differences(json.loads(run_file.read_text()))
        if diff:
            raise FileExistsError(
                f"{run_dir} holds an evaluation with another configuration (it differs in: "
                f"{', '.join(diff)}); its episodes cannot be mixed with this one. Re-run that "
                "command to resume it, pass another --out, or --overwrite to start fresh"
            )
        return True
    elif run_dir.exists() and any(run_dir.iterdir()):
        raise FileExistsError(
            f"{run_dir} exists and is not an activearena-eval run; pass another --out "
            "(or --overwrite to replace it)"
        )
    (run_dir / "policy").mkdir(parents=True, exist_ok=True)
    (run_dir / "policy" / "config.json").write_text(json.dumps(policy_config, indent=2))
    run_file.write_text(json.dumps(plan.to_json(), indent=1))
    return False


def reopen_unfinished_shards(plan: EvalPlan, run_dir: Path) -> None:
    """datatrove skips a shard it marked complete; one whose records lack episodes (deleted, or
    skipped as another process's records) is marked open again, so re-running the command plays them."""
    completions = Path(run_dir) / "logs" / "completions"
    for rank, shard in enumerate(plan.shards):
        marker = completions / f"{rank:05d}"
        if marker.is_file():
            done = read_records(records_dir(run_dir, shard))
            if any((shard.task, shard.split, k) not in done for k in shard.episodes):
                marker.unlink()


def run_eval(
    plan: EvalPlan,
    run_dir: Path,
    policy_config: dict,
    workers: int = 1,
    batch_size: int = 1,
    use_async_envs: bool = False,
    videos: int = 1,
    executor: str = "local",
    slurm: dict | None = None,
    overwrite: bool = False,
    progress: bool = True,
) -> dict | None:
    """Run (or resume) the plan in ``run_dir``; returns the merged overall metrics per split, or None
    when the jobs were submitted to Slurm (the merge job writes the results)."""
    run_dir = Path(run_dir).resolve()
    prepare_run(plan, run_dir, policy_config, overwrite)
    reopen_unfinished_shards(plan, run_dir)
    workers = max(1, min(workers, len(plan.shards)))
    step = EvalShardStep(plan, str(run_dir), batch_size, use_async_envs, videos, one_thread=workers > 1)
    if executor == "slurm":
        submit_slurm(
            step, len(plan.shards), MergeStep(plan, str(run_dir)), run_dir, "activearena-eval", slurm
        )
        return None
    if executor != "local":
        raise ValueError(f"executor must be 'local' or 'slurm', got {executor!r}")
    try:
        run_local(
            step, len(plan.shards), workers, run_dir / "logs", _Progress(plan, run_dir) if progress else None
        )
    finally:
        forget_loaded_policy()  # one worker runs in this process: the policy is kept for its shards only
    return merge_run(plan, run_dir)
