"""`activearena-slim-dataset --root SRC --out DST`: a copy of a built ActiveArena dataset holding only
what a LeRobot policy reads (the head video, ``observation.state``, ``action`` and LeRobot's index
columns), made with LeRobot's own ``remove_feature`` (what ``lerobot-edit-dataset --operation.type
remove_feature`` runs).

Why: a built dataset carries 24 per-frame annotation columns for the VLA suite (masks, boxes, camera
matrices, keyframes). LeRobot queries every column for every sample, so a policy that reads none of
them (ACT, diffusion, pi0.5) loads samples several times slower than it needs to
(``benchmarks/slim_dataset_loading.py`` measures it), and LeRobot's feature mapping turns
``action_target_mask`` (it starts with ``action``) into a second action output. Train those policies
on the slim copy. ``--vla`` keeps the annotation columns the VLA suite (``activearena_oft`` ...)
reads as well (the subtask index and the keyframe flags): its chunk-memory sample (13 head frames,
13 states, 16 actions) loads about twice as fast from that copy. Either copy keeps the episode
sidecars (``meta/activearena``).
"""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

# What a LeRobot policy trained on this benchmark reads, plus the columns LeRobot itself needs.
POLICY_COLUMNS = ("observation.images.head", "observation.state", "action")
LEROBOT_COLUMNS = ("timestamp", "frame_index", "episode_index", "index", "task_index")
SIDECARS = Path("meta/activearena")


def vla_columns() -> tuple[str, ...]:
    """The annotation columns the ActiveArena-VLA suite reads at training time."""
    from ..policies.activearena_vla.dataset_annotations import COLUMNS

    return tuple(c for c in COLUMNS if c not in LEROBOT_COLUMNS)


def columns_to_drop(features: dict, keep: tuple[str, ...] = ()) -> list[str]:
    """The columns of ``features`` that neither a policy nor LeRobot reads, except ``keep``.
    An unknown name in ``keep`` is an error."""
    unknown = [k for k in keep if k not in features]
    if unknown:
        raise ValueError(
            f"--keep names columns the dataset does not have: {unknown}; it has {sorted(features)}"
        )
    kept = set(POLICY_COLUMNS) | set(LEROBOT_COLUMNS) | set(keep)
    missing = [k for k in POLICY_COLUMNS if k not in features]
    if missing:
        raise ValueError(
            f"not an ActiveArena dataset: it lacks {missing} (built by activearena-build-dataset?)"
        )
    return [k for k in features if k not in kept]


def slim_dataset(root: str | Path, out: str | Path, repo_id: str | None = None, keep: tuple[str, ...] = ()):
    """Write the slim copy of the dataset at ``root`` to ``out`` and return it (a LeRobotDataset)."""
    from lerobot.datasets.dataset_tools import remove_feature
    from lerobot.datasets.lerobot_dataset import LeRobotDataset

    root, out = Path(root), Path(out)
    if not (root / "meta" / "info.json").is_file():
        raise FileNotFoundError(
            f"{root} holds no LeRobotDataset (no meta/info.json); pass the folder a build wrote"
        )
    source = LeRobotDataset(repo_id or f"local/{root.name}", root=root)
    drop = columns_to_drop(source.meta.features, keep)
    slim = remove_feature(source, drop, output_dir=out, repo_id=f"local/{out.name}")
    if (root / SIDECARS).is_dir():
        shutil.copytree(root / SIDECARS, out / SIDECARS)
    return slim


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(prog="activearena-slim-dataset", description=__doc__.split("\n\n")[0])
    p.add_argument("--root", required=True, help="a dataset activearena-build-dataset wrote")
    p.add_argument("--out", required=True, help="folder for the slim copy (must not exist, or --overwrite)")
    p.add_argument("--repo-id", help="the source's repo id (default local/<root folder name>)")
    p.add_argument("--keep", default="", help="annotation columns to keep as well, comma separated")
    p.add_argument(
        "--vla",
        action="store_true",
        help="keep the annotation columns the ActiveArena-VLA policies read (to train activearena_* on it)",
    )
    p.add_argument("--overwrite", action="store_true", help="replace an existing --out")
    args = p.parse_args(argv)
    out = Path(args.out)
    if out.exists():
        if not args.overwrite:
            p.error(f"{out} exists; pass --overwrite to replace it, or choose another --out")
        shutil.rmtree(out)
    keep = tuple(k.strip() for k in args.keep.split(",") if k.strip())
    if args.vla:
        keep = tuple(dict.fromkeys(keep + vla_columns()))
    try:
        ds = slim_dataset(args.root, out, args.repo_id, keep)
    except (ValueError, FileNotFoundError) as e:
        p.error(str(e))
    print(
        f"{out}: {ds.meta.total_episodes} episodes, {ds.meta.total_frames} frames, "
        f"columns {', '.join(ds.meta.features)}"
    )


if __name__ == "__main__":
    main()
