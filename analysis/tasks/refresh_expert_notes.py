"""Add to a built dataset the expert notes the current expert writes and the build's expert did not
(e.g. ``grasp_misses``, which ``--policy.miss_weight`` reads), without re-rendering it.

    python analysis/tasks/refresh_expert_notes.py outputs/datasets/BUILD [outputs/datasets/BUILD_vla]

Each episode is played again by the expert (``run_expert_episode`` with the build's plan: its seed,
split and demonstration options; no rendering). The expert is deterministic, so its commands must
equal the dataset's ``action`` column frame for frame; an episode that differs stops the script
before anything is written. The notes of every episode are then merged into its sidecar in the build
and in each further root given (a slim copy), keys already there left as they are.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
from tqdm import tqdm

from lerobot_activearena.episodes.rollout import DemoVariation, run_expert_episode


def build_variation(plan: dict) -> DemoVariation:
    fields = DemoVariation.__dataclass_fields__
    return DemoVariation(**{k: v for k, v in plan.items() if k in fields})


def dataset_actions(root: Path) -> dict[int, np.ndarray]:
    import pandas as pd

    files = sorted((root / "data").glob("*/*.parquet"))
    table = pd.concat([pd.read_parquet(f, columns=["episode_index", "action"]) for f in files])
    return {int(e): np.stack(g["action"].values) for e, g in table.groupby("episode_index")}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("root", type=Path, help="the build (activearena-build-dataset --root)")
    p.add_argument("copies", type=Path, nargs="*", help="slim copies whose sidecars get the notes too")
    args = p.parse_args()
    meta = args.root / "meta/activearena"
    plan = json.loads((meta / "build.json").read_text())["plan"]
    variation = build_variation(plan)
    size = tuple(plan["image_size"])
    episodes = [json.loads(line) for line in (meta / "episodes.jsonl").read_text().splitlines()]
    recorded = dataset_actions(args.root)
    notes = {}
    for ep in tqdm(episodes, desc="expert episodes", unit="ep"):
        i = int(ep["episode_index"])
        result = run_expert_episode(ep["task"], ep["seed"], ep["split"], image_size=size, **vars(variation))
        played = np.asarray(result.actions, np.float32)
        if played.shape != recorded[i].shape or not np.allclose(played, recorded[i], atol=1e-5):
            raise SystemExit(
                f"episode {i} (seed {ep['seed']}): the expert's commands now differ from the dataset's; "
                "the build was made by another expert: rebuild it instead"
            )
        notes[i] = result.sidecar["expert_notes"]
    for root in [args.root, *args.copies]:
        for i, new in notes.items():
            path = root / f"meta/activearena/sidecars/episode_{i:06d}.json"
            side = json.loads(path.read_text())
            side["expert_notes"] = new | (side.get("expert_notes") or {})
            path.write_text(json.dumps(side))
    added = sum(bool(n.get("grasp_misses")) for n in notes.values())
    print(
        f"{len(notes)} episodes checked; notes merged into {1 + len(args.copies)} roots ({added} with grasp_misses)"
    )


if __name__ == "__main__":
    main()
