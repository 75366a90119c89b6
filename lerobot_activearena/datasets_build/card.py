"""The dataset card a build writes to ``<root>/README.md`` and ``push`` uploads: LeRobot's card
template filled with the release's facts (tasks by category, features, keyframe definitions, seeds,
build command and versions, license, citation), all read back from the finished dataset."""

from __future__ import annotations

import json
from collections import Counter, defaultdict
from pathlib import Path

from ..tasks import CATEGORIES, get_task
from .features import COLUMN_DOCS, IMAGE_KEY, META_DIR

LICENSE = "apache-2.0"
TAGS = ["activearena", "active-perception", "mujoco", "simulation", "bimanual"]
PAPER_TITLE = "ActiveArena: Benchmarking and Understanding Active Perception in Robotic Manipulation"
CITATION = """@article{li2026activearena,
  title  = {ActiveArena: Benchmarking and Understanding Active Perception in Robotic Manipulation},
  author = {Li, Yibo and Zhou, Enshen and Chen, Rui and Ding, Yanjun and Liu, Mengzhen and Han, Yi and
            Zhan, Jiabo and Wang, Lipeng and Zhang, Shanghang and Sheng, Lu},
  year   = {2026}
}"""
# The paper's task counts per category (35 tasks); the card shows how many this release holds.
PAPER_TASKS_PER_CATEGORY = {"SS": 5, "SL": 16, "ML": 6, "MD": 3, "IA": 5}

KEYFRAMES = """- `subtask_keyframe`: frame 0 and the first frame after every change of the subtask label.
- `motion_keyframe`: frame 0 plus causally confirmed motion events, at least 5 frames apart: a gripper
  entering or leaving a stable open (>= 0.8) or closed (<= 0.2) state for 2 frames; the onset (4th
  frame with |change| > 0.005 rad) and end (6th still frame) of a head-pitch or torso-yaw rotation.
- `chunk_keyframe`: every 16th frame (t mod 16 == 0), the action-chunk boundaries."""


def _read_jsonl(path: Path) -> list[dict]:
    return (
        [json.loads(line) for line in path.read_text().splitlines() if line.strip()] if path.is_file() else []
    )


def _seed_ranges(seeds: list[int]) -> str:
    """[0, 1, 2, 5] -> "0-2, 5"."""
    out, seeds = [], sorted(seeds)
    i = 0
    while i < len(seeds):
        j = i
        while j + 1 < len(seeds) and seeds[j + 1] == seeds[j] + 1:
            j += 1
        out.append(str(seeds[i]) if i == j else f"{seeds[i]}-{seeds[j]}")
        i = j + 1
    return ", ".join(out)


def _tasks_table(episodes: list[dict], skipped: list[dict], root: Path) -> str:
    by_task = defaultdict(list)
    for e in episodes:
        by_task[e["task"]].append(e)
    skips = Counter(s["task"] for s in skipped)
    lines = []
    for cat, cat_name in CATEGORIES.items():
        tasks = sorted(t for t in by_task if get_task(t).category == cat)
        held = f"{len(tasks)} of the paper's {PAPER_TASKS_PER_CATEGORY[cat]} tasks"
        lines += [f"### {cat}: {cat_name} ({held})", ""]
        if not tasks:
            lines += ["None in this release.", ""]
            continue
        lines += [
            "| task | step limit | episodes | frames | scene seeds | expert failures skipped | example instruction |",
            "|---|---|---|---|---|---|---|",
        ]
        for t in tasks:
            eps = by_task[t]
            first = json.loads(
                (root / META_DIR / "sidecars" / f"episode_{eps[0]['episode_index']:06d}.json").read_text()
            )
            lines.append(
                f"| `{t}` | {get_task(t).max_episode_steps} | {len(eps)} | {sum(e['length'] for e in eps)} | "
                f"{_seed_ranges([e['seed'] for e in eps])} | {skips[t]} | {first['instruction']} |"
            )
        lines.append("")
    return "\n".join(lines)


def _features_table(info: dict) -> str:
    lines = ["| column | dtype | shape | meaning |", "|---|---|---|---|"]
    for name, ft in info["features"].items():
        doc = COLUMN_DOCS.get(name, "LeRobot's standard column")
        lines.append(f"| `{name}` | {ft['dtype']} | {tuple(ft['shape'])} | {doc} |")
    return "\n".join(lines)


def card_kwargs(root: Path) -> dict:
    """What fills LeRobot's card template (``create_lerobot_dataset_card`` / ``push_to_hub``)."""
    root = Path(root)
    build = json.loads((root / META_DIR / "build.json").read_text())
    info = json.loads((root / "meta/info.json").read_text())
    episodes = _read_jsonl(root / META_DIR / "episodes.jsonl")
    skipped = _read_jsonl(root / META_DIR / "skipped.jsonl")
    plan, versions = build["plan"], build.get("versions", {})
    minutes = build["frames"] / info["fps"] / 60
    duration = f"{minutes / 60:.2f} h" if minutes >= 60 else f"{minutes:.1f} min"
    recipe = build.get("recipe") or {}
    if recipe:
        about = f"Built from the recipe `datasets_build/{recipe['file']}`: {recipe.get('description') or ''}"
        if recipe.get("overrides"):
            flags = ", ".join(f"`{f}`" for f in recipe["overrides"])
            about += (
                f" **This build overrode {flags} on the command line** (the tables below are what it holds)."
            )
    else:
        about = ""
    reasons = Counter(s["reason"].split(":")[0] for s in skipped)
    description = f"""Expert demonstrations of the **ActiveArena** active-perception benchmark, rebuilt on MuJoCo
as a LeRobot plugin (`lerobot_env_activearena`). {about}

- **{build["episodes"]} episodes, {build["frames"]} frames ({duration} at {info["fps"]} fps)** of
  {len(plan["tasks"])} tasks, split `{plan["split"]}`; the scripted expert (sector search with memory,
  look-at, IK arm primitives) on an Astribot S1 class dual-arm robot with a moving head camera and
  torso yaw. Only episodes the expert solved are kept.
- Observation: the head camera `{IMAGE_KEY}` and the 18-D joint state; action: 18-D absolute targets
  (two 7-joint arms and grippers, torso yaw, head pitch). Every frame carries the paper's process
  annotations (subtask, stage, focus object, visibility and discovery masks, camera intrinsics and
  extrinsics, end-effector poses) and three keyframe indicators.
- `meta/activearena/` holds the build plan (`build.json`), each episode's task and seed
  (`episodes.jsonl`), the seeds the expert failed with reasons (`skipped.jsonl`), and one sidecar per
  episode (instruction, object map, subtask definitions, transition log).

## Tasks

{_tasks_table(episodes, skipped, root)}
## Features

{_features_table(info)}

Matrices are flattened row-major (3x3 -> 9, 4x4 -> 16); object masks have one slot per task object
(the sidecar's `objects`) padded with -1; the paper's NaN (no camera target) is stored as 0 with
`camera_target_active` = 0.

## Keyframes

{KEYFRAMES}

The paper's models read a stride-16 history: 12 frames before the current one, 16 frames apart.

```python
from lerobot.datasets.lerobot_dataset import LeRobotDataset

history = [-16 * k / {info["fps"]} for k in range(12, -1, -1)]
ds = LeRobotDataset("{plan["repo_id"]}", delta_timestamps={{"{IMAGE_KEY}": history, "observation.state": history}})
```

## Seeds

Scene seeds per task are listed above; the same seed rebuilds the same scene, trajectory and
annotations. With `episodes`, seeds `{plan["seed_start"]}` upwards are tried first and an expert failure
is replaced from the shard's reserve block. Evaluation manifests draw seeds from 100000 up, so no
episode here is an evaluation scene. Expert failures skipped: {len(skipped)}
({", ".join(f"{k}: {v}" for k, v in reasons.most_common()) or "none"}).

## Build

```bash
{build.get("command") or "activearena-build-dataset (command not recorded)"}
```

Versions: lerobot_env_activearena {build["package_version"]}, LeRobot {build["lerobot_version"]},
MuJoCo {versions.get("mujoco", "?")}, Python {versions.get("python", "?")}. Re-running the command
with these versions rebuilds this dataset.
"""
    return {
        "tags": TAGS,
        "license": LICENSE,
        "repo_id": plan["repo_id"],
        "dataset_description": description,
        "paper": PAPER_TITLE,
        "url": "the Build section below (package, command and versions that made this dataset)",
        "citation_bibtex": CITATION,
    }


def dataset_card(root: Path):
    """LeRobot's ``DatasetCard`` for the dataset at ``root``."""
    from lerobot.datasets.dataset_metadata import LeRobotDatasetMetadata
    from lerobot.datasets.utils import create_lerobot_dataset_card

    kwargs = card_kwargs(root)
    meta = LeRobotDatasetMetadata(kwargs["repo_id"], root=root)
    return create_lerobot_dataset_card(dataset_info=meta.info, **kwargs)


def write_card(root: Path) -> Path:
    path = Path(root) / "README.md"
    path.write_text(dataset_card(root).content)
    return path
