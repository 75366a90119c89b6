"""Keyframe definitions and memory views against hand-worked trajectories and the paper's example."""

import numpy as np
import pytest

from lerobot_activearena.annotations.keyframes import (
    chunk_keyframes,
    dedup,
    eef_events,
    gripper_events,
    memory_frames,
    memory_view,
    motion_keyframes,
    retrieval_positions,
    rotation_events,
    stride_sequence,
    subtask_keyframes,
)
from lerobot_activearena.sim.action import ACTION_NAMES


def test_chunk_keyframes_every_16_frames():
    k = chunk_keyframes(40)
    assert list(np.flatnonzero(k)) == [0, 16, 32] and k.dtype == np.int8
    with pytest.raises(ValueError):
        chunk_keyframes(5, chunk=0)


def test_subtask_keyframes_at_start_and_changes():
    s = [1, 1, 1, 2, 2, 3, 3, 3, 4]
    assert list(np.flatnonzero(subtask_keyframes(s))) == [0, 3, 5, 8]
    assert len(subtask_keyframes([])) == 0


def test_memory_view_is_recent_h_strictly_before_t():
    k = chunk_keyframes(100)  # 0, 16, 32, 48, 64, 80, 96
    assert memory_view(64, k, history=3) == [16, 32, 48]  # 64 itself is excluded
    assert memory_view(65, k, history=3) == [32, 48, 64]
    assert memory_view(0, k, history=12) == [] and memory_view(50, k, history=0) == []


def test_planner_stride_sequence_and_retrieval_match_the_papers_example():
    frames = stride_sequence(89, history=12)
    assert frames == [9, 25, 41, 57, 73, 89]
    assert retrieval_positions(frames, [0, 45]) == [0, 3]
    assert (
        stride_sequence(300, history=12)[0] == 300 - 12 * 16 and len(stride_sequence(300, history=12)) == 13
    )
    assert stride_sequence(5) == [5]


def test_gripper_events_need_two_frames_in_a_stable_state():
    #            O  O  O  B    B    C    C    C    B    O    O
    g = np.array([1, 1, 1, 0.5, 0.5, 0.1, 0.1, 0.1, 0.5, 0.9, 0.9])
    # leaves "open" (confirmed at 4), enters "closed" (6), enters "open" again (10): the single
    # "between" frame at 8 is never confirmed.
    assert gripper_events(g) == [4, 6, 10]
    assert gripper_events(np.full(20, 0.45)) == []  # holding an object half-closed: no event
    assert gripper_events([1.0, 0.1, 1.0, 0.1]) == []  # flicker never persists


def test_rotation_onset_after_four_frames_and_end_after_a_gap_of_six():
    q = np.zeros(40)
    q[10:18] = 0.01 * np.arange(1, 9)  # rotating at frames 10..17
    q[18:] = q[17]
    assert rotation_events(q) == [13, 23]  # onset confirmed at the 4th moving frame; end at the 6th still
    # a 3-frame pause is merged into one rotation
    q2 = np.concatenate(
        [
            np.zeros(5),
            0.01 * np.arange(1, 7),
            np.full(3, 0.06),
            0.06 + 0.01 * np.arange(1, 7),
            np.full(10, 0.12),
        ]
    )
    assert rotation_events(q2) == [8, 25]
    jitter = np.zeros(20)
    jitter[5:8] = [0.01, 0.02, 0.03]  # 3 moving frames (then it holds): too short to be an onset
    jitter[8:] = 0.03
    assert rotation_events(jitter) == []
    assert rotation_events(np.cumsum(np.full(30, 0.004))) == []  # below 0.005 rad per frame


def test_eef_turn_and_stop_events():
    dt = 1 / 15
    x_leg = [[0.01 * i, 0, 0] for i in range(6)]  # moving along +x, frames 0..5
    y_leg = [[0.05, 0.01 * i, 0] for i in range(1, 5)]  # then along +y, frames 6..9
    still = [[0.05, 0.04, 0]] * 4  # stops: frames 10..13
    p = np.array(x_leg + y_leg + still)
    assert eef_events(p) == [6, 10]  # 90 deg turn at 6, stop at 10
    assert np.linalg.norm(p[1] - p[0]) / dt > 0.001


def test_dedup_keeps_frames_at_least_delta_apart():
    assert dedup([0, 3, 4, 10, 12, 20, 20]) == [0, 10, 20]
    assert dedup([7, 2, 2]) == [2, 7]


def test_motion_keyframes_union_of_state_events_deduplicated():
    length = 60
    x = np.zeros((length, len(ACTION_NAMES)))
    col = {n: i for i, n in enumerate(ACTION_NAMES)}
    x[:, col["left_gripper"]] = 1.0
    x[30:, col["left_gripper"]] = 0.1  # closes at 30 -> leave-open confirmed at 31
    x[10:18, col["torso_yaw"]] = 0.02 * np.arange(1, 9)
    x[18:, col["torso_yaw"]] = 0.16  # onset 13, end 23
    x[40:48, col["head_pitch"]] = 0.01 * np.arange(1, 9)
    x[48:, col["head_pitch"]] = 0.08  # onset 43 (2 frames after nothing else), end 53
    k = motion_keyframes(x)
    assert k.dtype == np.int8 and len(k) == length
    assert list(np.flatnonzero(k)) == [0, 13, 23, 31, 43, 53]
    # adding an end-effector stop 2 frames after the gripper event: de-duplicated away
    p = np.zeros((length, 3))
    p[:34, 0] = 0.01 * np.arange(34)
    p[34:, 0] = p[33, 0]
    assert list(np.flatnonzero(motion_keyframes(x, {"left": p}))) == [0, 13, 23, 31, 43, 53]
    p[34:, 0] = p[33, 0]
    p[:40, 0] = 0.01 * np.arange(40)
    p[40:, 0] = p[39, 0]  # stop at 40 is 9 frames after 31 but 3 before 43: kept, 43 dropped
    assert list(np.flatnonzero(motion_keyframes(x, {"left": p}))) == [0, 13, 23, 31, 40, 53]


def test_motion_keyframes_are_causal():
    rng = np.random.default_rng(0)
    x = np.cumsum(rng.normal(0, 0.01, (80, len(ACTION_NAMES))), axis=0)
    x[:, [7, 15]] = rng.uniform(0, 1, (80, 2))
    full = motion_keyframes(x)
    for t in (10, 37, 79):
        assert (motion_keyframes(x[: t + 1]) == full[: t + 1]).all()


def test_memory_frames_per_write_policy():
    sub = subtask_keyframes([0] * 10 + [1] * 30 + [2] * 20)  # keyframes 0, 10, 40
    assert memory_frames("chunk", 64, history=12) == [0, 16, 32, 48]
    assert (
        memory_frames("chunk", 250, history=12)[0] == 250 - 16 * 12
        and len(memory_frames("chunk", 250, history=12)) == 12
    )
    assert memory_frames("subtask", 40, history=12, keyframes=sub) == [0, 10]  # 40 itself is not memory yet
    assert memory_frames("subtask", 59, history=1, keyframes=sub) == [40]
    assert memory_frames("none", 64, history=12) == [] and memory_frames("chunk", 64, history=0) == []
    with pytest.raises(ValueError, match="write policy"):
        memory_frames("planned", 5)
    with pytest.raises(ValueError, match="motion_keyframe"):
        memory_frames("motion", 5)
