"""Can a memory frame carry what an inspection task reads? For each vision cache
(`activearena-cache-vision`) of an IA build (check_block_color: the gray block's back patch), the
per-token MLP probe of `vision_feature_probe.py` learns the expert's reading (the patch colour) from
the frame's visual tokens, at the frames around the reading (``--window`` either side of the frame
the expert read it) and, as the control, at the first frames of the placing subtask (the block turned
back, the patch out of view: what a memory-free policy sees when it must choose the pad). Train on
episodes below ``--heldout-from``, score the rest, beside the majority class.

    python analysis/policies/reading_probe.py --root outputs/datasets/cpu_block_200_p16_192 \\
        outputs/vision_cache/cpu_block_200_p16_192_grounded_objects.safetensors
"""

from __future__ import annotations

import argparse
import glob
import json
import sys
from pathlib import Path

import numpy as np
import torch

sys.path.insert(0, str(Path(__file__).parent))
from vision_feature_probe import cache_tokens, probe  # noqa: E402


def reading_frames(root: Path, window: int, place_subtask: int):
    """Per frame of the build (dataset index order): the episode, the reading's label (-1 where the
    episode has none), whether it lies within ``window`` of the reading and whether it is among the
    first ``2 * window + 1`` frames of the placing subtask; and the label names."""
    import pandas as pd

    data = pd.concat(pd.read_parquet(f) for f in sorted(glob.glob(f"{root}/data/*/*.parquet")))
    data = data.sort_values("index")
    episodes, frames = data["episode_index"].to_numpy(), data["frame_index"].to_numpy()
    subtask = data["subtask_index"].to_numpy()
    read_at, value = {}, {}
    for path in sorted((root / "meta/activearena/sidecars").glob("episode_*.json")):
        notes = json.loads(path.read_text())["expert_notes"]
        ep = int(path.stem.split("_")[1])
        inspection = notes["inspections"][-1]
        read_at[ep], value[ep] = int(inspection["frame"]), str(inspection["reading"])
    names = sorted(set(value.values()))
    labels = np.array([names.index(value[e]) for e in episodes])
    near = np.abs(frames - np.array([read_at[e] for e in episodes])) <= window
    place_start = {}
    for e, f, s in zip(episodes, frames, subtask, strict=True):
        if s == place_subtask:
            place_start[e] = min(place_start.get(e, f), f)
    after = np.array(
        [
            e in place_start and 0 <= f - place_start[e] <= 2 * window
            for e, f in zip(episodes, frames, strict=True)
        ]
    )
    return episodes, labels, near, after, names


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("caches", nargs="+", type=Path, help="vision caches of the build")
    p.add_argument("--root", type=Path, required=True, help="the full build (with its annotations)")
    p.add_argument("--window", type=int, default=2, help="frames either side of the reading")
    p.add_argument("--place-subtask", type=int, default=4, help="the placing subtask's index")
    p.add_argument("--heldout-from", type=int, default=160, help="episodes from this one are held out")
    args = p.parse_args(argv)
    episodes, labels, near, after, names = reading_frames(args.root, args.window, args.place_subtask)
    held = episodes >= args.heldout_from
    y = torch.tensor(labels)
    print(
        f"readings {names}; {int(near.sum())} frames at the reading, {int(after.sum())} at the placing's start"
    )
    print("| vision cache | frames | train accuracy | held-out accuracy | majority class, held out |")
    print("|---|---|---|---|---|")
    for cache in args.caches:
        tokens = cache_tokens(cache, len(labels))
        for name, rows in (("at the reading", near), ("placing starts", after)):
            train, test = torch.tensor(rows & ~held), torch.tensor(rows & held)
            pred = probe(tokens, y, train)
            acc = [(pred[m] == y[m]).float().mean().item() for m in (train, test)]
            majority = torch.bincount(y[train]).argmax()
            print(
                f"| {cache.name} | {name} | {acc[0]:.3f} | {acc[1]:.3f} | "
                f"{(y[test] == majority).float().mean().item():.3f} |"
            )


if __name__ == "__main__":
    main()
