"""Every run of the paper's internal-baseline manifest (13) and ActiveArena-Fixed has a preset in
configs/policy that parses; each trains for 2 steps on the tiny backbone through lerobot-train, saves,
reloads and plays one episode through lerobot-eval and activearena-eval. The presets with their own
end-to-end test (OFT K=6, Fixed, GR00T, FAST, Plan) are played there; the others here."""

import json

import pytest
from helpers.params import DATASET_REPO
from helpers.policy_runs import FIXED, PRESETS, RUNS, play_both, train_preset
from lerobot.configs.train import TrainPipelineConfig

EXTRA = [FIXED, "oft_subtask_planned_12_ws_planner"]  # ActiveArena-Fixed; Plan's planner
PLAYED_ELSEWHERE = {
    "oft_subtask_action_6_ws": "test_oft_policy",
    "oft_subtask_action_12_ws_fixed": "test_oft_policy",
    "gr00t_subtask_action_12_ws": "test_groot_policy",
    "fast_subtask_action_12_ws": "test_fast_policy",
    "oft_subtask_planned_12_ws": "test_plan_policy",
    "oft_subtask_planned_12_ws_planner": "test_plan_policy",
}
TYPE_OF = {"gr00t": "activearena_groot", "fast": "activearena_fast"}


def test_every_run_has_a_preset_that_parses():
    assert sorted(p.stem for p in PRESETS.glob("*.json")) == sorted(RUNS + EXTRA)
    for name in RUNS + EXTRA:
        cfg = TrainPipelineConfig.from_pretrained(
            PRESETS / f"{name}.json", cli_args=[f"--dataset.repo_id={DATASET_REPO}"]
        )
        expected = TYPE_OF.get(name.split("_")[0], "activearena_oft")
        if "planned" in name:
            expected = "activearena_planner" if name.endswith("planner") else "activearena_plan"
        assert cfg.policy.type == expected, name
        assert cfg.job_name == name and cfg.batch_size == 7  # the paper's batch per GPU
        assert (
            json.loads((PRESETS / f"{name}.json").read_text())["policy"]["vlm_path"]
            == "Qwen/Qwen3-VL-2B-Instruct"
        )


@pytest.mark.parametrize("name", [r for r in RUNS if r not in PLAYED_ELSEWHERE])
def test_the_preset_trains_reloads_and_plays_through_both_evaluators(
    name, tiny_vlm, bell_count_dataset, tmp_path
):
    ckpt = train_preset(
        PRESETS / f"{name}.json",
        bell_count_dataset,
        tiny_vlm,
        tmp_path / "train",
        "--policy.state_hidden=32",
        "--policy.subtask_max_tokens=4",
    )
    assert json.loads((ckpt / "config.json").read_text())["history"] == int(name.split("_")[3])
    play_both(ckpt, tmp_path)
