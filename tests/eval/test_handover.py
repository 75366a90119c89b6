"""Handover rollouts (analysis/policies/handover_eval.py): the expert plays up to a point, the policy after."""

import json
from pathlib import Path

import pytest

from lerobot_activearena.eval.handover import handover_step, play_with_handover, torso_offset
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


def torso_yaw(into: list):
    from lerobot_activearena.sim.action import TORSO_YAW

    return lambda vec: into.append(float(vec.envs[0].unwrapped.sim.state()[TORSO_YAW]))


def off_by(rad: float, start: int, called: list):
    offset = torso_offset(rad, start)

    def adjust(t, actions):
        called.append(t)
        return offset(t, actions)

    return adjust


def test_the_expert_drives_until_the_handover_and_the_policy_after():
    """On a saved tiny (untrained) checkpoint: the expert alone (``never``) rings the bell, and the policy
    from the start does not (an ``adjust_expert`` changes what runs before the handover, and only from
    its step): it plays to the step limit or until a validity check ends its episode (its
    flailing can knock the bell over, depending on the machine's float rounding)."""
    with policy_in_env(
        SAVED / "checkpoint",
        "click_bell_rotate_view",
        "id",
        str(SAVED / "tiny_qwen3_vl"),
        expert_channel=True,
    ) as (policy, processors, vec, env_cfg, logs):
        seed = env_cfg.seed_base
        records, yaws = [], []
        for handover in (10**9, 0):
            yaw = []
            play_with_handover(policy, processors, vec, seed, handover, render_callback=torso_yaw(yaw))
            records.append(json.loads(sorted(logs.rglob("*.jsonl"))[0].read_text().splitlines()[-1]))
            yaws.append(yaw)
        assert vec.step.__func__ is type(vec).step  # the env's own step is back after each episode
        turned, called, decided = [], [], {False: [], True: []}
        off = off_by(0.06, 8, called)
        predict = policy.predict_action_chunk
        for replan, yaw in (
            (False, turned),
            (True, []),
        ):  # the env steps at which a chunk is decided (the callback also runs at the reset)
            policy.predict_action_chunk = lambda b, at=decided[replan], y=yaw: (
                at.append(len(y) - 1) or predict(b)
            )
            play_with_handover(
                policy,
                processors,
                vec,
                seed,
                20,
                render_callback=torso_yaw(yaw),
                adjust_expert=None if replan else off,
                replan=replan,
            )
        policy.predict_action_chunk = predict
        n = policy.config.n_action_steps
    plain = yaws[0]
    assert called == list(range(20))  # the expert's steps only, the policy's after
    assert 20 % n and all(t % n == 0 for t in decided[False])  # a decision every n steps from step 0
    assert 20 in decided[True] and 20 + n in decided[True]  # replan: a new chunk at the handover
    assert [t for t in decided[True] if t < 20] == [t for t in decided[False] if t < 20]
    assert turned[:8] == plain[:8]  # the expert's own commands before step 8
    assert abs(turned[19] - plain[19]) > 0.03  # then a torso turned elsewhere
    expert, policy_alone = records
    assert expert["success"] and expert["steps"] < 137
    assert not policy_alone["success"]
    assert policy_alone["steps"] == 137 or (
        0 < policy_alone["steps"] < 137 and policy_alone["failure_reason"]
    )
