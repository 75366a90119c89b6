"""Evaluate one shard: LeRobot's own rollout loop (``lerobot.scripts.lerobot_eval.rollout``) over the
shard's manifest episodes with N vector envs. The env appends one record per finished episode to
``records/<shard>/`` the moment it ends, so a killed shard keeps its finished episodes and a re-run
plays only the others."""

from __future__ import annotations

import json
import logging
from contextlib import contextmanager, nullcontext
from pathlib import Path

import numpy as np

from .protocol import EvalPlan, EvalShard, register_policy_types, uses_expert_channel

log = logging.getLogger(__name__)


def records_dir(run_dir: Path, shard: EvalShard) -> Path:
    return Path(run_dir) / "records" / shard.name


def read_records(folder: Path) -> dict[tuple[str, str, int], dict]:
    """Finished episodes under ``folder`` keyed by (task, split, manifest index); the first record of
    an episode wins, and a line cut short by a kill is ignored."""
    out: dict[tuple[str, str, int], dict] = {}
    for f in sorted(Path(folder).rglob("*.jsonl")):
        for rec in _lines(f):
            out.setdefault((rec["task"], rec["split"], int(rec["episode"])), rec)
    for f in sorted(Path(folder).rglob(f"*{POLICY_STATS}")):  # what the policy counted (e.g. FAST's decodes)
        for rec in _lines(f):
            key = (rec["task"], rec["split"], int(rec["episode"]))
            if key in out:
                out[key].setdefault("policy_stats", rec["policy_stats"])
    return out


POLICY_STATS = ".policy_stats"  # JSON lines a shard writes beside the env's records


def _lines(path: Path):
    for line in path.read_text().splitlines():
        try:
            rec = json.loads(line)
        except ValueError:  # a line cut short by a kill
            continue
        if rec.get("episode") is not None:
            yield rec


def stats_at_episode_ends(snapshots: list[list[dict]], done) -> list[dict]:
    """Each env's policy counts as they stood after its episode's last step: ``snapshots[t]`` is
    ``policy.rollout_stats()`` after the action of step t; ``done`` is the rollout's cumulative
    (envs, steps) done mask. LeRobot's rollout keeps stepping an env that ended until the whole
    batch has, so the policy's final counts would include those extra chunks."""
    ends = [int(row.to(int).argmax()) if bool(row.any()) else len(row) - 1 for row in done]
    return [snapshots[t][b] for b, t in enumerate(ends)]


def write_policy_stats(folder: Path, shard: EvalShard, episodes: list[int], stats: list[dict]) -> None:
    """One line per episode of a rollout with the policy's own counts (``policy.rollout_stats()``)."""
    import os

    with open(Path(folder) / f"policy_{os.getpid()}{POLICY_STATS}", "a") as f:
        for k, st in zip(episodes, stats, strict=True):
            f.write(
                json.dumps({"task": shard.task, "split": shard.split, "episode": k, "policy_stats": st})
                + "\n"
            )


def env_config(plan: EvalPlan, task: str, split: str, log_dir: Path | None):
    from ..envs.configs import ActiveArenaEnvConfig

    options = dict(plan.env)
    return ActiveArenaEnvConfig(
        task=task,
        split=split,
        fixed_view=plan.fixed_view,
        seed_base=plan.seed_base,
        expert_channel=uses_expert_channel(plan.policy.get("type")),
        episode_log_dir=None if log_dir is None else str(log_dir),
        **options,
    )


_LOADED: dict = {}  # this process's policy and processors for the plan it last ran, and the RNG after loading


def loaded_policy(run_dir: Path, plan: EvalPlan, load):
    """``load()``'s policy and processors, kept for the worker's next shard of the same plan (loading a
    2B backbone costs more than a short task's episodes). A shard that reuses them starts from the RNG
    state loading left, so its episodes are those of a fresh process."""
    from lerobot.utils.random_utils import get_rng_state, set_rng_state

    key = (str(Path(run_dir).resolve()), json.dumps(plan.policy, sort_keys=True), plan.policy_path)
    if _LOADED.get("key") != key:
        _LOADED.clear()  # one policy at a time in memory
        loaded = load()
        _LOADED.update(key=key, loaded=loaded, rng=get_rng_state())
        return loaded
    set_rng_state(_LOADED["rng"])
    return _LOADED["loaded"]


def forget_loaded_policy() -> None:
    """Drop the kept policy (a run ended, or a shard failed and may have left it unusable)."""
    _LOADED.clear()


def video_path(run_dir: Path, shard: EvalShard, episode: int) -> Path:
    return Path(run_dir) / "videos" / f"{shard.task}_{shard.split}_{episode:03d}.mp4"


def run_shard(
    plan: EvalPlan,
    shard: EvalShard,
    run_dir: Path,
    batch_size: int = 1,
    use_async_envs: bool = False,
    videos: int = 1,
) -> dict:
    """Play the shard's unfinished episodes; returns {"episodes": n finished, "ran": n played now}."""
    import torch
    from lerobot.configs.policies import PreTrainedConfig
    from lerobot.envs.factory import make_env_pre_post_processors
    from lerobot.envs.utils import close_envs
    from lerobot.policies import make_policy, make_pre_post_processors
    from lerobot.scripts import lerobot_eval
    from lerobot.utils.device_utils import get_safe_torch_device
    from lerobot.utils.io_utils import write_video
    from lerobot.utils.random_utils import set_seed
    from tqdm import trange

    run_dir = Path(run_dir)
    folder = records_dir(run_dir, shard)
    folder.mkdir(parents=True, exist_ok=True)
    done = read_records(folder)
    pending = [k for k in shard.episodes if (shard.task, shard.split, k) not in done]
    if not pending:
        return {"episodes": len(shard.episodes), "ran": 0}
    # the run shows its own per-shard and overall bars instead of one per rollout
    register_policy_types()  # a fresh worker process: LeRobot's types and the plugins' ones
    lerobot_eval.trange = lambda *a, **k: trange(*a, **{**k, "disable": True})

    cfg = PreTrainedConfig.from_pretrained(run_dir / "policy")
    cfg.pretrained_path = (
        Path(plan.policy_path) if plan.policy_path else None
    )  # a Hub id or a folder, as lerobot-eval
    env_cfg = env_config(plan, shard.task, shard.split, folder)
    # as lerobot-eval seeds its run: a shard that plays a whole task and split samples what lerobot-eval samples
    set_seed(plan.seed_base)
    device = get_safe_torch_device(cfg.device)

    def load():
        with _quiet_stats_warning(cfg):
            policy = make_policy(cfg=cfg, env_cfg=env_cfg)
        policy.eval()
        processors = make_pre_post_processors(
            policy_cfg=cfg,
            pretrained_path=cfg.pretrained_path,
            preprocessor_overrides={"device_processor": {"device": str(policy.config.device)}},
        )
        return policy, *processors

    policy, preprocessor, postprocessor = loaded_policy(run_dir, plan, load)
    env_pre, env_post = make_env_pre_post_processors(env_cfg=env_cfg, policy_cfg=cfg)
    want_video = set(shard.episodes[:videos])
    fps = env_cfg.fps
    ran = 0
    # one vector env per batch size, kept for the shard's later batches: starting the env processes
    # (imports, scene build) costs more than a batch of short episodes; each rollout resets with its seeds
    opened: dict[int, dict] = {}
    try:
        for start in range(0, len(pending), batch_size):
            batch = pending[start : start + batch_size]
            if len(batch) not in opened:
                opened[len(batch)] = env_cfg.create_envs(n_envs=len(batch), use_async_envs=use_async_envs)
            envs = opened[len(batch)]
            vec = next(iter(next(iter(envs.values())).values()))
            record = batch[0] in want_video and not video_path(run_dir, shard, batch[0]).exists()
            frames: list[np.ndarray] = []

            def render(env, frames=frames):
                frames.append(env.envs[0].render() if hasattr(env, "envs") else env.call("render")[0])

            snapshots: list[list[dict]] = []  # the policy's own counts after every step

            def snapshot(policy, snapshots=snapshots):
                snapshots.append(policy.rollout_stats())

            try:
                with (
                    torch.no_grad(),
                    torch.autocast(device_type=device.type) if cfg.use_amp else nullcontext(),
                ):
                    data = lerobot_eval.rollout(
                        vec,
                        policy,
                        env_pre,
                        env_post,
                        preprocessor,
                        postprocessor,
                        seeds=[plan.seed_base + k for k in batch],
                        render_callback=render if record else None,
                        # LeRobot's hook after every select_action (named for world-model latents)
                        predicted_latents_callback=snapshot
                        if callable(getattr(policy, "rollout_stats", None))
                        else None,
                    )
            except Exception as exc:  # name what did not finish; what did is recorded and resumes
                forget_loaded_policy()
                raise RuntimeError(
                    f"{shard.name}: episodes {batch} did not finish ({type(exc).__name__}: {exc}). The "
                    f"episodes finished before are recorded in {folder}; fix the cause and re-run the command "
                    "to resume"
                ) from exc
            if snapshots:
                write_policy_stats(folder, shard, batch, stats_at_episode_ends(snapshots, data["done"]))
            if record:
                last = int(torch.argmax(data["done"][0].to(int)))
                path = video_path(run_dir, shard, batch[0])
                path.parent.mkdir(parents=True, exist_ok=True)
                write_video(str(path), np.stack(frames[: last + 2]), fps)
            got = read_records(folder)
            missing = [k for k in batch if (shard.task, shard.split, k) not in got]
            if missing:
                raise RuntimeError(
                    f"{shard.name}: episodes {missing} ended without an episode record in {folder}"
                )
            ran += len(batch)
            log.info(
                "%s: %d/%d episodes",
                shard.name,
                len(shard.episodes) - len(pending) + ran,
                len(shard.episodes),
            )
    finally:
        for envs in opened.values():
            close_envs(envs)
    return {"episodes": len(shard.episodes), "ran": ran}


class _DropStatsWarning(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        return "instantiating a policy from scratch" not in record.getMessage()


@contextmanager
def _quiet_stats_warning(cfg):
    """LeRobot warns that a policy built from scratch normalises with infinite values until it has a
    dataset's statistics; a policy that normalises nothing (every mode IDENTITY: the scripted expert)
    needs none, so the warning would only mislead."""
    modes = getattr(cfg, "normalization_mapping", {}) or {}
    silent = bool(modes) and all(str(getattr(m, "value", m)) == "IDENTITY" for m in modes.values())
    root, drop = logging.getLogger(), _DropStatsWarning()
    if silent:
        root.addFilter(drop)
    try:
        yield
    finally:
        root.removeFilter(drop)
