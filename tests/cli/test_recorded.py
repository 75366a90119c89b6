"""lerobot_activearena/cli/recorded.py: protocol episodes with a hook after each step's checks."""

import pytest

from lerobot_activearena.cli.recorded import run_recorded
from lerobot_activearena.tasks.shapes import pressing

BELL = "click_bell_rotate_view"
EXPERT = ["--policy.type=activearena_expert", "--policy.device=cpu", "--env.render_pixels=false"]


def test_the_hook_sees_every_step_of_the_episode_and_the_task_is_restored_after():
    original = pressing.PressDeviceTask.__dict__["evaluate"]
    seen = []

    def on_step(task, sim, scene):
        seen.append((task.name, scene.seed, float(sim.data.time)))

    records = run_recorded(pressing.PressDeviceTask, on_step, EXPERT, BELL, "id", "0", label="hooked")
    assert len(records) == 1 and records[0]["success"]
    assert {(name, seed) for name, seed, _ in seen} == {(BELL, records[0]["scene_seed"])}
    assert len(seen) >= records[0]["steps"]  # once per control step at least
    assert [t for *_, t in seen] == sorted(t for *_, t in seen)  # in the episode's order
    assert pressing.PressDeviceTask.__dict__["evaluate"] is original


def test_the_task_is_restored_when_the_evaluation_fails():
    original = pressing.PressDeviceTask.__dict__["evaluate"]
    with pytest.raises(SystemExit):  # activearena-eval: unknown task selector
        run_recorded(pressing.PressDeviceTask, lambda *a: None, EXPERT, "no_such_task", "id", "0")
    assert pressing.PressDeviceTask.__dict__["evaluate"] is original
