"""`activearena-build-dataset`: run the scripted expert and write the episodes it solves as a
LeRobotDataset v3 (head video, state, action, instruction, every per-frame annotation, keyframe
flags), sharded through datatrove (local processes or Slurm) and merged with LeRobot's aggregation.
Re-running the same command resumes an interrupted build."""

from __future__ import annotations

import argparse
import json
import logging
import shlex
import sys
from pathlib import Path

from ..datasets_build.features import MAX_OBJECTS
from ..datasets_build.pipeline import build_dataset
from ..datasets_build.plan import BuildPlan
from ..datasets_build.recipe import RECIPE_KEYS, load_recipe
from .args import image_size, int_ranges


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument(
        "--recipe",
        type=Path,
        default=None,
        help="a build recipe (datasets_build/train_id.json, datasets_build/preview.json); flags override it",
    )
    p.add_argument("--repo-id", default=None, help="e.g. your-hf-user/activearena_train_id (or the recipe's)")
    p.add_argument(
        "--root", type=Path, required=True, help="local dataset folder (written when the build completes)"
    )
    p.add_argument(
        "--tasks", default=None, help="task name, category (SS/SL/ML/MD/IA), 'all' (default), or a comma list"
    )
    p.add_argument("--split", default=None, choices=["id", "ood"], help="scene sampling (default id)")
    g = p.add_mutually_exclusive_group()
    g.add_argument(
        "--episodes", type=int, help="kept (solved) episodes per task (default 100, the paper's ID set)"
    )
    g.add_argument(
        "--seeds",
        type=int_ranges,
        help="explicit scene seeds, e.g. 0-9,42 (failures are skipped and recorded)",
    )
    p.add_argument("--seed-start", type=int, default=None, help="first seed with --episodes (default 0)")
    p.add_argument(
        "--episodes-per-shard",
        type=int,
        default=None,
        help="episodes per shard, the unit of resume (default 10)",
    )
    p.add_argument(
        "--image-size",
        default=None,
        help="head video HEIGHTxWIDTH, 3:4 (default 384x512, the paper's); rendered at that size",
    )
    p.add_argument(
        "--search-overshoot",
        type=float,
        default=None,
        help="recovery demonstrations: the probability that the expert's search sweeps an empty end "
        "sector on to the torso's joint limit before turning back (default 0: the benchmark's expert)",
    )
    p.add_argument(
        "--action-noise",
        type=float,
        default=None,
        help="perturbed demonstrations (DART): the standard deviation in rad of a smooth noise added to "
        "the arm and view joints the simulator executes, faded out in presses; the dataset records the "
        "expert's own commands, which lead back to its path (default 0: the benchmark's expert)",
    )
    p.add_argument(
        "--face-jitter",
        type=float,
        default=None,
        help="off-centre demonstrations: each torso turn that puts an object in front of an arm is off by a "
        "uniform angle in +/- this many rad and the arm reaches from there (default 0: the benchmark's expert)",
    )
    p.add_argument(
        "--turn-error",
        type=float,
        default=None,
        help="turn-recovery demonstrations: the torso yaw executed in an episode's first 16 frames is off the "
        "expert's command by a uniform angle in +/- this many rad (at most 0.4), the heading a policy's first "
        "chunk lands at; the dataset records the expert's commands, which turn back (default 0: the "
        "benchmark's expert)",
    )
    p.add_argument(
        "--turn-error-subtask",
        type=int,
        default=None,
        help="with --turn-error: the first 16 frames of this subtask (its number in the task's list, >= 2; "
        "check_block_color's place: 4) are turned off too, by a second draw (default 0: the first chunk only)",
    )
    p.add_argument(
        "--grasp-miss",
        type=float,
        default=None,
        help="grasp-retry demonstrations: each pick's first try runs with the arm 0.5-1 x this many m above the "
        "grasp point and as far beside it across the fingers (at most 0.08), shuts on nothing and is tried "
        "again; the dataset records the expert's commands, and the sidecars the missed tries' frames "
        "(--policy.miss_weight) (default 0: the benchmark's expert)",
    )
    p.add_argument(
        "--reading-variants",
        type=int,
        default=None,
        help="counterfactual readings (IA tasks whose layout draws its reading with SceneDraft.draw_reading): "
        "seed s plays scene s // N with its hidden reading shifted by s %% N, so every scene is demonstrated "
        "with N readings and the decisions they lead to; a policy cannot tell them apart without reading "
        "(default 1: the benchmark's scenes)",
    )
    p.add_argument(
        "--decision-period",
        type=int,
        default=None,
        help="chunk-aligned demonstrations: the expert's search reacts to what the camera shows only "
        "every N frames, where a policy executing N-action chunks plans its next one, so no chunk of a "
        "demonstration depends on a view the policy has not seen yet (default 1: the benchmark's expert)",
    )
    p.add_argument(
        "--press-arm",
        choices=["left", "right"],
        default=None,
        help="one-arm demonstrations: the count-and-press tasks' expert presses with this arm wherever the "
        "button is (as the click_bell expert always uses the left), so which arm moves does not depend "
        "on the count (default: the arm on the button's half of the fan, the benchmark's expert)",
    )
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: all cores)")
    p.add_argument("--executor", default="local", choices=["local", "slurm"])
    p.add_argument(
        "--slurm",
        type=json.loads,
        default=None,
        help='Slurm options for datatrove\'s SlurmPipelineExecutor as JSON, e.g. \'{"partition": "cpu", "time": "04:00:00"}\'',
    )
    p.add_argument("--work-dir", type=Path, default=None, help="shards and logs (default: <root>.work)")
    p.add_argument("--keep-shards", action="store_true", help="keep the per-shard datasets after merging")
    p.add_argument("--overwrite", action="store_true", help="replace an existing --root / unfinished build")
    p.add_argument(
        "--push-to-hub", action="store_true", help="upload with LeRobotDataset.push_to_hub when done"
    )
    p.add_argument("--private", action="store_true")
    return p


def main(argv: list[str] | None = None) -> None:
    p = parser()
    args = p.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    if args.executor == "slurm" and not args.slurm:
        p.error('--executor slurm needs --slurm \'{"partition": ..., "time": ...}\'')
    try:
        recipe = load_recipe(args.recipe) if args.recipe else None
        plan = make_plan(args, recipe)
        release = recipe_release(args, recipe)
    except (ValueError, FileNotFoundError) as exc:
        p.error(str(exc))
    summary = build_dataset(
        plan,
        args.root,
        work_dir=args.work_dir,
        workers=args.workers,
        executor=args.executor,
        slurm=args.slurm,
        overwrite=args.overwrite,
        keep_shards=args.keep_shards,
        push_to_hub=args.push_to_hub,
        private=args.private,
        recipe=release,
        command=shlex.join(["activearena-build-dataset", *(sys.argv[1:] if argv is None else argv)]),
    )
    if summary is None:
        print(f"submitted to Slurm; the merge job writes {args.root}")
        return
    print(
        f"{args.root}: {summary['episodes']} episodes, {summary['frames']} frames, {summary['skipped']} skipped seeds"
        + (f", shortfall {summary['shortfall']}" if summary["shortfall"] else "")
    )


def recipe_release(args: argparse.Namespace, recipe: dict | None) -> dict | None:
    """The recipe's file name and description, and which of its values the command line replaced
    (the dataset card says so)."""
    if recipe is None:
        return None
    overrides = [f"--{k.replace('_', '-')}" for k in RECIPE_KEYS if getattr(args, k, None) is not None]
    return {
        "file": args.recipe.name,
        "description": recipe["description"],
        "overrides": overrides,
    }


def make_plan(args: argparse.Namespace, recipe: dict | None = None) -> BuildPlan:
    """The build plan from the recipe (``load_recipe``'s; default: ``args.recipe`` if given) with the
    command line's flags on top."""
    if recipe is None:
        recipe = load_recipe(args.recipe) if args.recipe else dict(RECIPE_KEYS)

    def pick(name):
        value = getattr(args, name)
        return recipe[name] if value is None else value

    repo_id = pick("repo_id")
    if not repo_id:
        raise ValueError("--repo-id is required (or a --recipe that names one)")
    seeds, episodes = args.seeds, args.episodes
    if seeds is None and episodes is None:  # neither flag: the recipe's choice, else 100 episodes
        seeds, episodes = recipe["seeds"], recipe["episodes"]
        if isinstance(seeds, str):
            seeds = int_ranges(seeds)
        if seeds is None and episodes is None:
            episodes = 100
    return BuildPlan(
        repo_id=repo_id,
        split=pick("split"),
        tasks=[pick("tasks")],
        episodes=episodes,
        seeds=seeds,
        seed_start=pick("seed_start"),
        episodes_per_shard=pick("episodes_per_shard"),
        max_objects=MAX_OBJECTS,
        image_size=image_size(pick("image_size")),
        search_overshoot=float(pick("search_overshoot")),
        action_noise=float(pick("action_noise")),
        decision_period=pick("decision_period"),  # an int, or the clear error of a recipe's 16.5
        press_arm=pick("press_arm"),
        face_jitter=float(pick("face_jitter")),
        reading_variants=pick("reading_variants"),
        turn_error=float(pick("turn_error")),
        turn_error_subtask=pick("turn_error_subtask"),
        grasp_miss=float(pick("grasp_miss")),
    )


if __name__ == "__main__":
    main()
