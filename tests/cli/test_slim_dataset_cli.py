"""`activearena-slim-dataset`: the copy a LeRobot policy trains on keeps every frame's image, state and
action and drops the annotation columns (so LeRobot maps no annotation to a policy feature)."""

import numpy as np
import pytest
from helpers.params import DATASET_REPO
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.utils.feature_utils import dataset_to_policy_features

from lerobot_activearena.cli.slim_dataset import (
    LEROBOT_COLUMNS,
    POLICY_COLUMNS,
    columns_to_drop,
    main as slim_main,
)


def test_slim_copy_keeps_frames_and_drops_annotations(bell_count_dataset, tmp_path, capsys):
    out = tmp_path / "slim"
    slim_main(["--root", str(bell_count_dataset), "--repo-id", DATASET_REPO, "--out", str(out)])
    assert "episodes" in capsys.readouterr().out
    full = LeRobotDataset(DATASET_REPO, root=bell_count_dataset)
    slim = LeRobotDataset("local/slim", root=out)
    assert set(slim.meta.features) == set(POLICY_COLUMNS) | set(LEROBOT_COLUMNS)
    assert "action_target_mask" in full.meta.features  # the source is untouched
    assert (slim.num_episodes, slim.num_frames) == (full.num_episodes, full.num_frames)
    for i in (0, full.num_frames // 2, full.num_frames - 1):
        a, b = full[i], slim[i]
        for key in ("action", "observation.state", "observation.images.head", "episode_index", "task"):
            if key == "task":
                assert a[key] == b[key]
            else:
                np.testing.assert_array_equal(a[key].numpy(), b[key].numpy(), err_msg=key)
    # LeRobot's feature mapping: the full dataset has a second ACTION (action_target_mask), the slim one not
    assert "action_target_mask" in dataset_to_policy_features(full.meta.features)
    outputs = {
        k for k, f in dataset_to_policy_features(slim.meta.features).items() if f.type.name == "ACTION"
    }
    assert outputs == {"action"}
    np.testing.assert_allclose(slim.meta.stats["action"]["mean"], full.meta.stats["action"]["mean"])

    with pytest.raises(SystemExit):  # an existing --out is never replaced silently
        slim_main(["--root", str(bell_count_dataset), "--out", str(out)])
    slim_main(
        ["--root", str(bell_count_dataset), "--out", str(out), "--overwrite", "--keep", "target_uv_norm"]
    )
    assert "target_uv_norm" in LeRobotDataset("local/slim", root=out).meta.features


def test_slim_refuses_unknown_columns_and_non_datasets(tmp_path):
    features = {k: {} for k in (*POLICY_COLUMNS, *LEROBOT_COLUMNS, "stage")}
    assert columns_to_drop(features) == ["stage"]
    with pytest.raises(ValueError, match="does not have"):
        columns_to_drop(features, keep=("stag",))
    with pytest.raises(ValueError, match="lacks"):
        columns_to_drop({"action": {}})
    with pytest.raises(SystemExit):
        slim_main(["--root", str(tmp_path), "--out", str(tmp_path / "x")])


def test_vla_copy_serves_the_same_annotations(bell_count_dataset, tmp_path):
    from lerobot_activearena.policies.activearena_vla.dataset_annotations import DatasetAnnotations

    plain, vla = tmp_path / "slim", tmp_path / "slim_vla"
    slim_main(["--root", str(bell_count_dataset), "--repo-id", DATASET_REPO, "--out", str(plain)])
    slim_main(["--root", str(bell_count_dataset), "--repo-id", DATASET_REPO, "--out", str(vla), "--vla"])
    with pytest.raises(ValueError, match="--vla"):  # the plain copy names the fix
        DatasetAnnotations(plain)
    full, copy = DatasetAnnotations(bell_count_dataset, DATASET_REPO), DatasetAnnotations(vla)
    assert len(copy.ds.meta.features) < len(full.ds.meta.features)
    frames = full.ds.num_frames
    for i in range(0, frames, max(1, frames // 40)):
        assert copy.subtask(i) == full.subtask(i)
        for policy in ("chunk", "subtask", "motion"):
            assert copy.memory_indices(i, policy, 12) == full.memory_indices(i, policy, 12)
    # the keyframe flags carry information: some frame has a subtask keyframe after its first
    assert any(len(full.subtask_keyframes(i)[1]) > 1 for i in range(frames))
