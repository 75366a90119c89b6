"""The learning curve reads a checkpoint in a fresh process, as its CLI does."""

import subprocess
import sys

import pytest
import torch
from lerobot.configs.types import FeatureType, PolicyFeature
from lerobot.policies.act.configuration_act import ACTConfig


def test_a_checkpoints_image_size_is_read_in_a_fresh_process(tmp_path):
    """A checkpoint's config names its policy type; a fresh process (the CLI's) must have LeRobot's
    types registered before reading it."""
    cfg = ACTConfig(device="cpu")
    cfg.input_features = {
        "observation.images.head": PolicyFeature(FeatureType.VISUAL, (3, 96, 128)),
        "observation.state": PolicyFeature(FeatureType.STATE, (18,)),
    }
    cfg.output_features = {"action": PolicyFeature(FeatureType.ACTION, (18,))}
    cfg.save_pretrained(tmp_path)
    code = (
        "import sys; from pathlib import Path; "
        "from lerobot_activearena.eval.learning_curve import image_size; print(image_size(Path(sys.argv[1])))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code, str(tmp_path)], capture_output=True, text=True, timeout=300
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split()[-2:] == ["(96,", "128)"]


def test_open_loop_scoring_reads_the_scored_builds_annotations_not_the_training_builds(bell_count_dataset):
    """A checkpoint's preprocessor names its training build; scored on another build (held-out
    episodes), the annotation step must read that build's, and send the history as images, since a
    vision cache's frame indices name the training build's frames."""
    from types import SimpleNamespace

    from helpers.params import DATASET_REPO
    from lerobot.lerobot_types import TransitionKey

    from lerobot_activearena.eval.learning_curve import read_annotations_from
    from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import (
        MEMORY_INDEX,
        ActiveArenaAnnotationStep,
    )

    step = ActiveArenaAnnotationStep(
        dataset_root="/nonexistent/training_build",
        repo_id="local/training_build",
        memory="chunk",
        history=4,
        think="subtask",
        cached_memory=True,
    )
    read_annotations_from(SimpleNamespace(steps=[step]), DATASET_REPO, bell_count_dataset)
    assert (step.dataset_root, step.repo_id, step.cached_memory) == (
        str(bell_count_dataset),
        DATASET_REPO,
        False,
    )
    out = step({TransitionKey.OBSERVATION: {}, TransitionKey.COMPLEMENTARY_DATA: {"index": [0]}})
    comp = out[TransitionKey.COMPLEMENTARY_DATA]
    assert MEMORY_INDEX not in comp
    assert isinstance(comp["subtask"][0], str) and comp["subtask"][0]


def test_the_annotation_step_refuses_frames_of_another_build(bell_count_dataset):
    """A checkpoint fine-tuned on another build keeps its saved annotation step, which reads the build
    it was trained on: frames whose episode (or index) that build does not have there are refused,
    not annotated with another episode's subtasks."""
    from helpers.params import DATASET_REPO
    from lerobot.lerobot_types import TransitionKey

    from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import (
        ActiveArenaAnnotationStep,
    )

    step = ActiveArenaAnnotationStep(
        dataset_root=str(bell_count_dataset), repo_id=DATASET_REPO, memory="chunk", history=4, think="subtask"
    )

    def batch(index, episode):
        comp = {"index": torch.tensor(index), "episode_index": torch.tensor(episode)}
        return {TransitionKey.OBSERVATION: {}, TransitionKey.COMPLEMENTARY_DATA: comp}

    out = step(batch([0, 1], [0, 0]))  # the first episode's first frames: annotated
    assert len(out[TransitionKey.COMPLEMENTARY_DATA]["subtask"]) == 2
    frames = len(step._ann.cols["episode_index"])
    for index, episode in (([0, 1], [0, 1]), ([frames], [1])):
        with pytest.raises(ValueError, match="dataset_root and repo_id"):
            step(batch(index, episode))


def _write_curve(folder, successes):
    import json

    folder.mkdir(parents=True)
    lines = [
        json.dumps({"step": 500 * (i + 1), "closed_loop": {"episodes": 50, "success": s, "indices": "50-99"}})
        for i, s in enumerate(successes)
    ]
    (folder / "curve.jsonl").write_text("\n".join(reversed(lines)) + "\n")  # order on disk is not assumed


def test_overlay_draws_a_pairs_measured_curves_on_one_axis_and_names_each_runs_best_step(tmp_path, capsys):
    from PIL import Image

    from lerobot_activearena.cli.learning_curve import main

    _write_curve(tmp_path / "a", [0.0, 40.0, 30.0])
    _write_curve(tmp_path / "b", [10.0, 10.0, 5.0])
    out = tmp_path / "fig" / "pair.png"
    main(["--overlay", f"chunk-12={tmp_path / 'a'}", f"memory-free={tmp_path / 'b'}", "--out", str(out)])
    printed = capsys.readouterr().out
    assert "chunk-12: 3 checkpoints, best step 1000 (40.0%)" in printed
    assert "memory-free: 3 checkpoints, best step 1000 (10.0%)" in printed  # the latest of a tie
    assert Image.open(out).size[0] > 0


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--overlay", "no-equals-sign", "--out", "x.png"], "LABEL=CURVE_DIR"),
        (["--overlay", "a=/nonexistent", "--out", "x.png"], "curve.jsonl not found"),
        (["--overlay", "a=/nonexistent", "--out", "folder"], "name the .png"),
        (["--out", "folder"], "give a train_dir and --task"),
    ],
)
def test_overlay_and_measure_modes_refuse_bad_arguments_by_name(argv, message, capsys):
    from lerobot_activearena.cli.learning_curve import main

    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    assert message in capsys.readouterr().err
