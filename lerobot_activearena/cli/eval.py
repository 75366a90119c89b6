"""`activearena-eval`: the ActiveArena protocol (or any task / split / episode selection) for any LeRobot
policy, as resumable shards on datatrove (local processes, or Slurm array jobs), merged into
lerobot-eval's output layout per split and a leaderboard report.

    activearena-eval --policy.type=activearena_expert --env.render_pixels=false --workers 2 --out outputs/protocol/expert
    activearena-eval --policy.path=outputs/train/run/checkpoints/last/pretrained_model --policy.device=cuda \\
        --batch-size 50 --async-envs --out outputs/protocol/oft
    activearena-eval --config_path=configs/env/activearena_fixed_id.json --config_path=configs/env/activearena_fixed_ood.json \\
        --policy.type=activearena_expert --out outputs/protocol/expert_fixed

`--policy.*` options are those of lerobot-eval; `--env.*` sets further options of the activearena env
(`render_pixels`, `episode_length`). Re-running the same command resumes a killed run.
"""

from __future__ import annotations

import argparse
import json
import logging
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import draccus
from lerobot.configs.policies import PreTrainedConfig

from ..envs.configs import ActiveArenaEnvConfig
from ..envs.manifests import DEFAULT_SEED_BASE
from ..eval.protocol import register_policy_types, uses_expert_channel
from .args import int_ranges

RESERVED_ENV = {
    "type",
    "task",
    "split",
    "fixed_view",
    "seed_base",
    "expert_channel",
    "episode_log_dir",
    "use_manifest",
}


@dataclass
class _PolicyArgs:
    policy: PreTrainedConfig | None = None


@dataclass
class _EnvArgs:
    env: ActiveArenaEnvConfig = field(default_factory=ActiveArenaEnvConfig)


def parse_policy(policy_args: list[str]):
    """A PreTrainedConfig from lerobot-eval style ``--policy.*`` arguments (``path`` or ``type``) of
    any policy type lerobot-eval knows."""
    register_policy_types()
    path = next((a.split("=", 1)[1] for a in policy_args if a.startswith("--policy.path=")), None)
    rest = [a for a in policy_args if not a.startswith("--policy.path=")]
    if path:
        cfg = PreTrainedConfig.from_pretrained(
            path, cli_overrides=[a.replace("--policy.", "--", 1) for a in rest]
        )
        cfg.pretrained_path = Path(path)
        return cfg, path
    if not any(a.startswith("--policy.type=") for a in rest):
        raise ValueError(
            "give the policy as in lerobot-eval: --policy.path=<checkpoint folder or Hub id>, or "
            "--policy.type=<type> (e.g. activearena_expert) for one built from scratch"
        )
    return draccus.parse(_PolicyArgs, args=rest).policy, None


def parse_env(env_args: list[str]) -> dict:
    """Further ActiveArenaEnvConfig options from ``--env.*`` (those the protocol does not set itself)."""
    for a in env_args:
        key = a[len("--env.") :].split("=", 1)[0]
        if key in RESERVED_ENV:
            raise ValueError(
                f"{a}: activearena-eval sets env.{key} itself; use --tasks, --splits, --fixed-view "
                "or a --config_path file instead"
            )
    env = draccus.parse(_EnvArgs, args=env_args).env
    given = {a[len("--env.") :].split("=", 1)[0] for a in env_args}
    return {k: getattr(env, k) for k in sorted(given)}


def config_file_defaults(paths: list[Path]) -> dict:
    """Selection settings from lerobot-eval config files (``configs/env/*.json``): the union of their
    splits; tasks, fixed view, episodes and batch settings must agree."""
    out: dict = {}
    splits: list[str] = []
    for path in paths:
        if not Path(path).is_file():
            raise FileNotFoundError(
                f"--config_path {path} not found (the protocol's files are in configs/env/)"
            )
        d = json.loads(Path(path).read_text())
        env, ev = d.get("env", {}), d.get("eval", {})
        if env.get("type") != "activearena":
            raise ValueError(
                f"{path}: env.type is {env.get('type')!r}; activearena-eval runs activearena configs"
            )
        vals = {
            "tasks": env.get("task", "all"),
            "fixed_view": bool(env.get("fixed_view", False)),
            "episodes": ev.get("n_episodes"),
            "batch_size": ev.get("batch_size"),
            "async_envs": ev.get("use_async_envs"),
            "seed_base": d.get("seed", DEFAULT_SEED_BASE),
        }
        for k, v in vals.items():
            if v is None:
                continue
            if k in out and out[k] != v:
                raise ValueError(f"{path}: {k}={v!r} disagrees with an earlier --config_path ({out[k]!r})")
            out[k] = v
        if env.get("split", "id") not in splits:
            splits.append(env.get("split", "id"))
    if splits:
        out["splits"] = ",".join(splits)
    return out


def check_features(cfg, env_options: dict, fixed_view: bool) -> None:
    """A pretrained policy's input / output features must be what the activearena env provides."""
    from lerobot.configs.types import FeatureType
    from lerobot.envs.utils import env_to_policy_features
    from lerobot.utils.constants import ACTION

    if not cfg.input_features and not cfg.output_features:
        return  # built from scratch: make_policy fills them from the env
    env_cfg = ActiveArenaEnvConfig(
        fixed_view=fixed_view, expert_channel=uses_expert_channel(cfg.type), **env_options
    )
    provided = env_to_policy_features(env_cfg)
    problems = []
    acted = {
        k: v for k, v in cfg.output_features.items() if k == ACTION
    }  # other outputs are training targets
    for key, feat in {**cfg.input_features, **acted}.items():
        have = provided.get(key)
        if have is None:
            problems.append(f"{key} {tuple(feat.shape)} is not provided")
        elif tuple(have.shape) != tuple(feat.shape):
            problems.append(
                f"{key} has shape {tuple(have.shape)} in the env, {tuple(feat.shape)} in the policy"
            )
            if have.type is FeatureType.VISUAL and len(feat.shape) == 3 and feat.shape[0] == 3:
                _, h, w = feat.shape  # LeRobot's policies hold images channel-first
                problems.append(
                    f"the policy was trained on {h}x{w} head images: add "
                    f"--env.observation_height={h} --env.observation_width={w}"
                )
    if problems:
        env_list = ", ".join(f"{k} {tuple(v.shape)}" for k, v in provided.items())
        raise ValueError(
            "the policy's features do not match the activearena env: "
            + "; ".join(problems)
            + f". The env provides {env_list}. Train the policy on an ActiveArena dataset "
            "(activearena-build-dataset) or evaluate it on the env it was trained for"
        )


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="activearena-eval",
        description=__doc__.split("\n\n")[0],
        epilog="--policy.<option>=... and --env.<option>=... are passed on as in lerobot-eval",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument(
        "--config_path",
        action="append",
        type=Path,
        default=[],
        help="a lerobot-eval config of configs/env/ (repeatable: their splits are combined)",
    )
    p.add_argument(
        "--tasks",
        default=None,
        help="task name, category (SS/SL/ML/MD/IA), 'all', or a comma list (default all)",
    )
    p.add_argument("--splits", default=None, help="comma list of id, ood (default id,ood)")
    g = p.add_mutually_exclusive_group()
    g.add_argument(
        "--episodes",
        type=int,
        default=None,
        help="the first N manifest episodes per task and split (default 50)",
    )
    g.add_argument(
        "--episode-indices", type=int_ranges, default=None, help="explicit manifest indices, e.g. 0-9,20"
    )
    p.add_argument(
        "--fixed-view",
        action="store_true",
        default=None,
        help="ActiveArena-Fixed: head and torso held at home",
    )
    p.add_argument(
        "--label", default=None, help="the policy's name in the report (default: policy type, + '-fixed')"
    )
    p.add_argument("--out", type=Path, required=True, help="run folder (re-run the same command to resume)")
    p.add_argument("--batch-size", type=int, default=None, help="vector envs per shard (default 1)")
    p.add_argument("--async-envs", action="store_true", default=None, help="one process per vector env")
    p.add_argument(
        "--episodes-per-shard", type=int, default=None, help="default: all episodes of a task and split"
    )
    p.add_argument("--workers", type=int, default=1, help="shards run at once on this machine")
    p.add_argument("--videos", type=int, default=1, help="rollout videos per shard (its first episodes)")
    p.add_argument("--executor", default="local", choices=["local", "slurm"])
    p.add_argument(
        "--slurm",
        type=json.loads,
        default=None,
        help='datatrove SlurmPipelineExecutor options as JSON, e.g. \'{"partition": "gpu", "time": "08:00:00", '
        '"gpus_per_task": 1}\'',
    )
    p.add_argument("--overwrite", action="store_true", help="discard an earlier run in --out and start fresh")
    return p


def main(argv: list[str] | None = None) -> None:
    from ..envs.manifests import PROTOCOL_EPISODES
    from ..eval.protocol import EvalPlan
    from ..eval.runner import run_eval

    argv = list(sys.argv[1:] if argv is None else argv)
    p = build_parser()
    args, extra = p.parse_known_args(argv)
    bad = [a for a in extra if not (a.startswith("--policy.") or a.startswith("--env."))]
    if bad:
        p.error(f"unrecognized arguments: {' '.join(bad)}")
    if any("=" not in a for a in extra):
        p.error("write --policy.* and --env.* options as --name=value")
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    if args.executor == "slurm" and not args.slurm:
        p.error('--executor slurm needs --slurm \'{"partition": ..., "time": ...}\'')
    try:
        defaults = config_file_defaults(args.config_path)

        def pick(name, fallback):
            v = getattr(args, name, None)
            return v if v is not None else defaults.get(name, fallback)

        cfg, policy_path = parse_policy([a for a in extra if a.startswith("--policy.")])
        env_options = parse_env([a for a in extra if a.startswith("--env.")])
        fixed_view = bool(pick("fixed_view", False))
        check_features(cfg, env_options, fixed_view)
        if args.episode_indices is not None:
            episodes = args.episode_indices
        else:
            episodes = list(range(pick("episodes", PROTOCOL_EPISODES)))
        with tempfile.TemporaryDirectory() as tmp:
            cfg.save_pretrained(tmp)
            policy_config = json.loads((Path(tmp) / "config.json").read_text())
        label = args.label or (cfg.type + ("-fixed" if fixed_view else ""))
        plan = EvalPlan(
            label=label,
            policy=policy_config,
            policy_path=policy_path,
            tasks=[pick("tasks", "all")],
            splits=pick("splits", "id,ood").split(","),
            episodes=episodes,
            fixed_view=fixed_view,
            env=env_options,
            seed_base=int(pick("seed_base", DEFAULT_SEED_BASE)),
            episodes_per_shard=args.episodes_per_shard or len(episodes),
        )
    except (ValueError, KeyError, FileNotFoundError) as exc:
        p.error(str(exc))
    batch = pick("batch_size", 1)
    if batch < 1 or args.workers < 1:
        p.error("--batch-size and --workers must be >= 1")
    print(
        f"activearena-eval: {plan.n_episodes} episodes ({len(plan.tasks)} tasks x {plan.splits} x "
        f"{len(plan.episodes)}) in {len(plan.shards)} shards -> {args.out}"
    )
    if args.executor == "local" and args.workers > len(plan.shards):
        per = -(-plan.n_episodes // args.workers)  # ceil: one block of episodes per worker
        print(
            f"activearena-eval: {len(plan.shards)} shards keep only {len(plan.shards)} of the {args.workers} "
            f"workers busy (a shard is one task and split by default); pass --episodes-per-shard "
            f"{max(1, per)} or fewer to use them all"
        )
    try:
        result = run_eval(
            plan,
            args.out,
            policy_config,
            workers=args.workers,
            batch_size=batch,
            use_async_envs=bool(pick("async_envs", False)),
            videos=args.videos,
            executor=args.executor,
            slurm=args.slurm,
            overwrite=args.overwrite,
        )
    except FileExistsError as exc:
        p.error(str(exc))
    if result is None:
        print(
            f"submitted to Slurm; the merge job writes {args.out}/<split>/eval_info.json and {args.out}/report"
        )
        return
    for split, o in result.items():
        print(
            f"{split}: {o['pc_success']:.1f}% success over {o['n_episodes']} episodes -> {args.out / split}/eval_info.json"
        )
    print(f"report: {args.out / 'report' / 'report.md'}")


if __name__ == "__main__":
    main()
