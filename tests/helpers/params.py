"""Constants and parameters the tests share (the fixtures built from them live in ``conftest.py``)."""

from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
BELL, COUNT = "click_bell_rotate_view", "count_target_press_button"
DATASET_REPO = "local/bench_id"  # the repo id of the session's small dataset (``bell_count_dataset``)
PREVIEW_RECIPE = REPO_ROOT / "datasets_build" / "preview.json"


def expert_task_params(selector: str = "all"):
    """The registered tasks (``task_names(selector)``) as parameters grouped by task, so ``--dist
    loadgroup`` sends a task's tests to one worker and the session cache serves its expert episodes
    once."""
    from lerobot_activearena.tasks import task_names

    return [pytest.param(t, marks=pytest.mark.xdist_group(t)) for t in task_names(selector)]
