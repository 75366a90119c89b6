"""Keyframe definitions and memory views against hand-worked trajectories and the paper's example."""

import numpy as np
import pytest

from lerobot_activearena.annotations.keyframes import (chunk_keyframes, memory_view, retrieval_positions,
                                                       stride_sequence, subtask_keyframes)


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
    assert memory_view(64, k, H=3) == [16, 32, 48]  # 64 itself is excluded
    assert memory_view(65, k, H=3) == [32, 48, 64]
    assert memory_view(0, k, H=12) == [] and memory_view(50, k, H=0) == []


def test_planner_stride_sequence_and_retrieval_match_the_papers_example():
    frames = stride_sequence(89, history=12)
    assert frames == [9, 25, 41, 57, 73, 89]
    assert retrieval_positions(frames, [0, 45]) == [0, 3]
    assert stride_sequence(300, history=12)[0] == 300 - 12 * 16 and len(stride_sequence(300, history=12)) == 13
    assert stride_sequence(5) == [5]
