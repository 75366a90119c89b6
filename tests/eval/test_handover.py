"""Handover rollouts (analysis/policies/handover_eval.py): the expert plays up to a point, the policy after."""

import json
from pathlib import Path

import pytest

from lerobot_activearena.eval.handover import handover_step, play_with_handover
from lerobot_activearena.eval.memory_frames import policy_in_env

SAVED = Path(__file__).resolve().parents[1] / "policies" / "fixtures" / "oft_saved_2026_11_25"


def test_handover_points_name_env_steps():
    subtasks = [1, 1, 1, 2, 2, 2, 2]
    assert handover_step("start", subtasks) == 0
    assert handover_step("subtask:2", subtasks) == 3 and handover_step("subtask:2+3", subtasks) == 6
    assert handover_step("never", subtasks) > 10**6
    with pytest.raises(ValueError, match="no subtask 3"):
        handover_step("subtask:3", subtasks)
    with pytest.raises(ValueError, match="use start, never"):
        handover_step("press", subtasks)


def test_the_expert_drives_until_the_handover_and_the_policy_after():
    """On a saved tiny (untrained) checkpoint: the expert alone (``never``) rings the bell, and the policy
    from the start does not: it plays to the step limit or until a validity check ends its episode (its
    flailing can knock the bell over, depending on the machine's float rounding)."""
    with policy_in_env(
        SAVED / "checkpoint",
        "click_bell_rotate_view",
        "id",
        str(SAVED / "tiny_qwen3_vl"),
        expert_channel=True,
    ) as (policy, processors, vec, env_cfg, logs):
        seed = env_cfg.seed_base
        records = []
        for handover in (10**9, 0):
            play_with_handover(policy, processors, vec, seed, handover)
            records.append(json.loads(sorted(logs.rglob("*.jsonl"))[0].read_text().splitlines()[-1]))
        assert vec.step.__func__ is type(vec).step  # the env's own step is back after each episode
    expert, policy_alone = records
    assert expert["success"] and expert["steps"] < 137
    assert not policy_alone["success"]
    assert policy_alone["steps"] == 137 or (
        0 < policy_alone["steps"] < 137 and policy_alone["failure_reason"]
    )
