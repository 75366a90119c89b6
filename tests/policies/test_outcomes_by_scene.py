"""analysis/policies/outcomes_by_scene.py: eval outcomes tabulated by a drawn scene parameter."""

import json

import pytest
from helpers.analysis_scripts import load
from helpers.params import COUNT

from lerobot_activearena.tasks import get_task
from lerobot_activearena.tasks.sampling import sample_scene


def _record(episode, success, state="", seed=None):
    return {
        "task": COUNT,
        "split": "id",
        "episode": episode,
        "scene_seed": 100000 + episode if seed is None else seed,
        "success": success,
        "failure_state": state,
    }


def test_outcomes_are_counted_per_value_and_each_episode_once():
    script = load("analysis/policies/outcomes_by_scene.py")
    episodes = [_record(0, True), _record(1, False, "CO"), _record(2, False, "CR"), _record(0, False, "CO")]
    table = script.tabulate(episodes, lambda r: "odd" if r["episode"] % 2 else "even")
    assert table["even"]["episodes"] == 2 and table["even"]["success"] == 1  # episode 0's first record wins
    assert table["even"]["failures"] == {"CR": 1}
    assert table["odd"] == {"episodes": 1, "success": 0, "failures": {"CO": 1}}


def test_the_parameter_comes_from_the_episodes_scene_seed(tmp_path):
    script = load("analysis/policies/outcomes_by_scene.py")
    shard = tmp_path / "records" / f"00000-{COUNT}-id"
    shard.mkdir(parents=True)
    records = [_record(k, k == 1, "" if k == 1 else "CO") for k in range(4)]
    (shard / "x.jsonl").write_text("".join(json.dumps(r) + "\n" for r in records))
    episodes = script.read_episodes(tmp_path, "id")
    assert len(episodes) == 4
    table = script.tabulate(episodes, script.scene_param("count"))
    counts = [sample_scene(get_task(COUNT), 100000 + k, "id").params["count"] for k in range(4)]
    assert {v: row["episodes"] for v, row in table.items()} == {c: counts.count(c) for c in set(counts)}
    assert table[counts[1]]["success"] == 1
    with pytest.raises(SystemExit, match="no parameter 'colour'"):
        script.tabulate(episodes, script.scene_param("colour"))
    with pytest.raises(SystemExit, match="no ood records"):
        script.read_episodes(tmp_path, "ood")
