"""ActiveArena-Plan's bookkeeping against the paper's worked example (x = 89, keyframes 0 and 45)
and its rules: capped planner input, uncapped executor memory without a duplicated current frame,
answers that parse back, malformed answers that change nothing but a counter."""

import pytest

from lerobot_activearena.annotations.keyframes import retrieval_positions
from lerobot_activearena.policies.activearena_plan.memory_bank import (
    MemoryBank,
    executor_memory,
    executor_prompt,
)
from lerobot_activearena.policies.activearena_planner.answers import (
    PlannerAnswer,
    parse_planner_answer,
    planner_prompt,
    planner_target,
    stride_frames,
)


def test_the_papers_worked_example():
    frames = stride_frames(89)
    assert frames == [9, 25, 41, 57, 73, 89]
    assert retrieval_positions(frames, [0, 45]) == [0, 3]
    target = planner_target(len(frames), "pick up the block", [0, 3])
    assert target == (
        '<think>Frames: 6 total (5 history + current). Now the subtask is "pick up the block"</think>'
        "<subtask>pick up the block</subtask><retrieval>[0, 3]</retrieval>"
    )
    assert parse_planner_answer(target, len(frames)) == PlannerAnswer("pick up the block", (0, 3))
    assert planner_prompt("Stack the blocks.").startswith(
        'Your task is: "Stack the blocks." The input images'
    )
    assert executor_prompt("pick up the block").endswith("Please think about the next action.")


def test_the_planner_sees_at_most_13_frames_the_executor_all_windows():
    assert stride_frames(300) == list(range(300 - 192, 301, 16))  # 12 history + current
    assert stride_frames(5) == [5] and stride_frames(300, history=None)[0] == 300 % 16
    # a keyframe seen before the capped window still selects from the uncapped history
    assert executor_memory(300, [0, 150]) == [12, 156, 300]
    assert executor_memory(32, [30]) == [32]  # x is in its own window: not twice
    assert retrieval_positions([9, 25], [20]) == [1]
    assert retrieval_positions([9, 25], [30]) == []  # a keyframe after the current frame is unknown
    with pytest.raises(ValueError):
        stride_frames(-1)


@pytest.mark.parametrize(
    "text",
    [
        "<subtask>a</subtask><retrieval>[0]</retrieval>",  # no think
        "<think>x</think><subtask>a</subtask>",  # no retrieval
        "<think>x</think><subtask>a</subtask><subtask>b</subtask><retrieval>[0]</retrieval>",
        "<think>x</think><subtask> </subtask><retrieval>[0]</retrieval>",  # empty subtask
        "<think>x</think><subtask>a</subtask><retrieval>[0, 6]</retrieval>",  # past the 6 images
        "<think>x</think><subtask>a</subtask><retrieval>[-1]</retrieval>",
        "<think>x</think><subtask>a</subtask><retrieval>[one]</retrieval>",
        "<think>x</think><subtask>a</subtask><retrieval>[0]</retrieval> trailing",
    ],
)
def test_malformed_answers_parse_to_none(text):
    assert parse_planner_answer(text, 6) is None


def test_the_bank_persists_deduplicates_and_counts_malformed_answers():
    bank = MemoryBank()
    bank.update(PlannerAnswer("find the block", (0,)), [0])
    bank.update(PlannerAnswer("pick up the block", (0, 1)), [0, 16])
    assert bank.frames == [0, 16] and bank.subtask == "pick up the block"
    bank.update(None, [0, 16, 32])
    assert bank.frames == [0, 16] and bank.subtask == "pick up the block" and bank.malformed == 1
    bank.update(PlannerAnswer("place the block", ()), [0, 16, 32, 48])  # nothing new: the bank stays
    assert bank.frames == [0, 16] and bank.executor_frames(48) == [0, 16, 48]
    assert parse_planner_answer("<think></think><subtask>a</subtask><retrieval>[]</retrieval>", 1) == (
        PlannerAnswer("a", ())
    )
