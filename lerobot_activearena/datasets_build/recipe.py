"""Build recipes: JSON files (``datasets_build/*.json`` at the repository's top level) that name a
release's repo id, tasks, split and seeds. ``activearena-build-dataset --recipe FILE`` reads one;
flags given on the command line override its values."""

from __future__ import annotations

import json
from pathlib import Path

# recipe key -> default when neither the recipe nor the command line sets it
RECIPE_KEYS = {
    "description": None,
    "repo_id": None,
    "tasks": "all",
    "split": "id",
    "episodes": None,
    "seeds": None,
    "seed_start": 0,
    "episodes_per_shard": 10,
    "image_size": "384x512",  # head video height x width (3:4)
    "search_overshoot": 0.0,  # recovery demonstrations: probability per empty end sector of a search
    "action_noise": 0.0,  # perturbed demonstrations: joint noise (rad) on the executed commands
    "decision_period": 1,  # chunk-aligned demonstrations: the search reacts every N frames
    "press_arm": None,  # one-arm demonstrations: the count-and-press tasks press with this arm
    "face_jitter": 0.0,  # off-centre demonstrations: the torso's facing turns off by up to this (rad)
    "reading_variants": 1,  # counterfactual readings: each scene demonstrated with N hidden readings
    "turn_error": 0.0,  # turn-recovery demonstrations: the first chunk's torso off by up to this (rad)
    "turn_error_subtask": 0,  # ... and the first chunk of this subtask's too (0: the first chunk only)
    "grasp_miss": 0.0,  # grasp-retry demonstrations: each pick's first try closes up to this far off (m)
}


def load_recipe(path: Path | str) -> dict:
    """The recipe at ``path`` with every key of ``RECIPE_KEYS`` present (defaults filled in)."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(
            f"no recipe at {path}; the released ones are in the repository's datasets_build/"
        )
    try:
        data = json.loads(path.read_text())
    except json.JSONDecodeError as exc:
        raise ValueError(f"recipe {path} is not valid JSON: {exc}") from exc
    if not isinstance(data, dict):
        raise ValueError(f"recipe {path} must be a JSON object with keys {sorted(RECIPE_KEYS)}")
    unknown = sorted(set(data) - set(RECIPE_KEYS))
    if unknown:
        raise ValueError(f"recipe {path}: unknown key(s) {unknown}; allowed: {sorted(RECIPE_KEYS)}")
    if data.get("episodes") is not None and data.get("seeds") is not None:
        raise ValueError(f"recipe {path} sets both 'episodes' and 'seeds'; keep one")
    return {**RECIPE_KEYS, **data}
