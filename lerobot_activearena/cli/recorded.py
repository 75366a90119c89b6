"""Protocol episodes with a step hook: run ``activearena-eval`` in this process with a task class's
``evaluate`` wrapped, so that a function sees the simulator after every step's checks, then hand back
the episode records. The analyses under ``analysis/policies/`` measure where a policy's arm went this
way, with the task's own predicates."""

from __future__ import annotations

import json
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path


def run_recorded(
    task_class: type,
    on_step: Callable,
    eval_args: Sequence[str],
    task: str,
    split: str,
    episode_indices: str,
    label: str = "recorded",
) -> list[dict]:
    """Run ``activearena-eval`` (one worker, no videos) on ``task``'s ``split`` episodes
    ``episode_indices`` with ``eval_args`` (the policy's options), calling ``on_step(task, sim, scene)``
    after each step's ``task_class.evaluate``. Returns the episode records, sorted by episode.
    ``task_class.evaluate`` is restored afterwards, also when the evaluation fails."""
    from .eval import main as activearena_eval

    evaluate = task_class.__dict__.get("evaluate")
    inherited = task_class.evaluate

    def recording(self, sim, scene, monitor):
        checks = inherited(self, sim, scene, monitor)
        on_step(self, sim, scene)
        return checks

    task_class.evaluate = recording
    try:
        with tempfile.TemporaryDirectory() as out:
            activearena_eval(
                [*eval_args, f"--tasks={task}", f"--splits={split}", "--workers=1", "--videos=0"]
                + [f"--episode-indices={episode_indices}", f"--label={label}", f"--out={out}"]
            )
            with (Path(out) / split / "episodes" / "records.jsonl").open() as f:
                records = [json.loads(line) for line in f]
    finally:
        if evaluate is None:
            del task_class.evaluate
        else:
            task_class.evaluate = evaluate
    return sorted(records, key=lambda r: r["episode"])
