"""analysis/policies/reading_probe.py: the frames it probes are those around the expert's reading
and those at the placing subtask's start, labelled with the episode's reading."""

import json

import numpy as np
import pandas as pd
from helpers.analysis_scripts import load


def _build(root, episodes):
    """A build's data table and sidecars: each episode (reading, frame read, placing's first frame, length)."""
    rows, index = [], 0
    (root / "data/chunk-000").mkdir(parents=True)
    (root / "meta/activearena/sidecars").mkdir(parents=True)
    for ep, (reading, read_at, place_from, length) in enumerate(episodes):
        for f in range(length):
            rows.append(
                {
                    "index": index,
                    "episode_index": ep,
                    "frame_index": f,
                    "subtask_index": 4 if f >= place_from else 2,
                }
            )
            index += 1
        notes = {"inspections": [{"object": "gray_block", "frame": read_at, "reading": reading}]}
        (root / f"meta/activearena/sidecars/episode_{ep:06d}.json").write_text(
            json.dumps({"expert_notes": notes})
        )
    pd.DataFrame(rows[::-1]).to_parquet(root / "data/chunk-000/file-000.parquet")  # out of index order


def test_reading_frames_marks_the_window_and_the_placing_start(tmp_path):
    script = load("analysis/policies/reading_probe.py")
    _build(tmp_path, [("red", 5, 12, 20), ("green", 3, 8, 15)])
    episodes, labels, near, after, names = script.reading_frames(tmp_path, window=1, place_subtask=4)
    assert names == ["green", "red"]
    assert len(labels) == 35 and (labels[:20] == 1).all() and (labels[20:] == 0).all()
    assert np.flatnonzero(near).tolist() == [4, 5, 6, 20 + 2, 20 + 3, 20 + 4]
    assert np.flatnonzero(after).tolist() == [12, 13, 14, 20 + 8, 20 + 9, 20 + 10]
    assert (episodes[:20] == 0).all()
