"""analysis/policies/training_scenes.py: a checkpoint re-played on its training scenes. Evaluation must
feed a memory policy what training fed it: with the env replaying a demonstration, the chunk from the
env's observation and the policy's own memory bank equals the chunk from the dataset sample of the same
frame (history from the delta timestamps), up to the video compression of the dataset's frames."""

import json

import numpy as np
import pytest
from helpers.analysis_scripts import ROOT, load
from helpers.params import BELL, DATASET_REPO
from helpers.policy_runs import train_preset

training_scenes = load("analysis/policies/training_scenes.py")
state_swap_probe = load("analysis/policies/state_swap_probe.py")
chunk_decision = load("analysis/policies/chunk_decision.py")


def test_the_env_replay_feeds_the_policy_its_training_inputs(tmp_path, tiny_vlm, bell_count_dataset):
    preset = ROOT / "configs/policy/small/oft_subtask_action_12_ws.json"
    ckpt = train_preset(preset, bell_count_dataset, tiny_vlm, tmp_path / "run")
    scenes = training_scenes.TrainingScenes(ckpt, DATASET_REPO, bell_count_dataset)
    episode = next(e for e, info in scenes.recorded.items() if info["task"] == BELL)

    aligned = scenes.replay(episode)
    assert [t for t, _, _ in aligned] == list(range(0, len(scenes.frames(episode)), 16))
    assert len(scenes.policy.memory(0)) == min(12, len(aligned))  # chunk memory: one frame per boundary
    # the largest gap where the policy reads memory frames (radians; 0.03 measured)
    gap = max(float(np.abs(a - b).max()) for _, a, b in aligned[1:])
    # controls: the dataset's sample 8 frames later (another image, state and history; 0.16), and
    # the env side's memory images blanked (0.8): a wrong memory shows
    shifted = max(float(np.abs(a - b).max()) for _, a, b in scenes.replay(episode, offset=8)[1:])
    scenes.policy.config.memory_ablation = "blank"
    both_blanked = max(float(np.abs(a - b).max()) for _, a, b in scenes.replay(episode)[1:])
    dataset_chunk = scenes.dataset_chunk

    def unblanked_dataset_chunk(index):
        scenes.policy.config.memory_ablation = "none"
        try:
            return dataset_chunk(index)
        finally:
            scenes.policy.config.memory_ablation = "blank"

    scenes.dataset_chunk = unblanked_dataset_chunk
    blanked = max(float(np.abs(a - b).max()) for _, a, b in scenes.replay(episode)[1:])
    scenes.dataset_chunk = dataset_chunk
    scenes.policy.config.memory_ablation = "none"
    assert gap < 0.4 * shifted < 0.4 * blanked, (gap, shifted, blanked)
    # blanked on both sides (the dataset batch's memory frames gray as the bank's): they agree again
    assert both_blanked < 0.4 * shifted, (both_blanked, shifted)

    # chunk_decision: the demonstration's turn at frame 16 read from its recorded actions, and the
    # prediction's from the chunk the policy predicts there
    ((ep, recorded_turns, predicted_turns),) = chunk_decision.decisions(scenes, [episode], at=16)
    frames = scenes.frames(episode)
    yaw = np.array([scenes.ds.hf_dataset[frames[16 + k]]["action"][16].item() for k in range(16)])
    assert ep == episode and recorded_turns == (yaw.max() - yaw.min() > 0.5)
    assert predicted_turns == chunk_decision.turns(scenes.dataset_chunk(frames[16]))
    assert chunk_decision.decisions(scenes, [episode], at=len(frames) - 8) == []  # no full chunk left
    # --probe's features: one row of action-query states per frame
    states, chunks, _ = chunk_decision.decision_probe.features(
        ckpt, DATASET_REPO, bell_count_dataset, [frames[16]]
    )
    assert states.shape[0] == 1 and np.isfinite(states).all()
    assert chunks.shape == (1, 16 * 18)  # the chunk decoded from those states (normalised)

    info, state = scenes.closed_loop(episode)
    assert "is_success" in info and state.shape == (18,)

    # what --show-demonstration puts in front of the policy: one of the two, the other its own
    env, _, _ = scenes.env(episode)
    obs, _ = env.reset(seed=scenes.recorded[episode]["seed"] + 1)  # another scene than the demonstration's
    recorded = scenes.ds.hf_dataset[scenes.frames(episode)[16]]
    state = scenes.demonstration_observation(episode, 16, obs, "state")
    assert np.array_equal(state["agent_pos"], recorded["observation.state"].numpy())
    assert state["pixels"]["head"] is obs["pixels"]["head"]
    image = scenes.demonstration_observation(episode, 16, obs, "image")
    assert image["agent_pos"] is obs["agent_pos"] and image["pixels"]["head"].dtype == np.uint8
    assert image["pixels"]["head"].shape == obs["pixels"]["head"].shape
    assert not np.array_equal(image["pixels"]["head"], obs["pixels"]["head"])
    with pytest.raises(ValueError, match="image' or 'state'"):
        scenes.demonstration_observation(episode, 16, obs, "memory")
    env.close()


def test_the_swap_probe_moves_a_state_policy_and_not_a_stateless_one(tmp_path, tiny_vlm, bell_count_dataset):
    preset = ROOT / "configs/policy/small/oft_subtask_action_12_ws.json"
    rows = {}
    for use_state in (True, False):
        out = tmp_path / f"state_{use_state}"
        ckpt = train_preset(
            preset, bell_count_dataset, tiny_vlm, out, f"--policy.use_state={str(use_state).lower()}"
        )
        scenes = training_scenes.TrainingScenes(ckpt, DATASET_REPO, bell_count_dataset)
        rows[use_state] = state_swap_probe.swap_errors(scenes, frame=50, pairs=2, episodes=[0, 1])
    for r in rows.values():
        assert r.shape == (2, 4) and np.isfinite(r).all() and (r[:, 3] > 0).all()
    # the swapped prediction against the image's episode: unchanged without state, moved with it
    assert np.array_equal(rows[False][:, 0], rows[False][:, 2])
    assert (rows[True][:, 0] != rows[True][:, 2]).all()


def test_a_chunk_turns_across_when_its_torso_yaw_spans_more_than_half_a_radian():
    chunk = np.zeros((16, 18))
    chunk[:, 16] = np.linspace(-0.95, -1.2, 16)  # centring a bell on the side it faces
    assert not chunk_decision.turns(chunk)
    chunk[:, 16] = np.linspace(-0.93, 0.95, 16)  # across to the other side
    assert chunk_decision.turns(chunk)


def test_the_decision_probe_reads_a_linearly_separable_label_and_not_noise():
    rng = np.random.default_rng(0)
    x = rng.normal(size=(60, 8))
    separable = x[:, 0] > 0
    assert int(chunk_decision.decision_probe.best_probe(x, separable).rstrip("%")) >= 90
    noise = rng.random(60) > 0.5
    assert int(chunk_decision.decision_probe.best_probe(x, noise).rstrip("%")) < 80


def test_chunk_decision_record_keys_checkpoints_by_run_and_step_and_plots_each_run(tmp_path):
    ckpt = tmp_path / "run_a" / "checkpoints" / "001250" / "pretrained_model"
    ckpt.mkdir(parents=True)
    assert chunk_decision.checkpoint_key(ckpt) == ("run_a", 1250)
    with pytest.raises(SystemExit, match="not a RUN/checkpoints"):
        chunk_decision.checkpoint_key(tmp_path / "run_a")
    record = tmp_path / "decisions.jsonl"
    assert chunk_decision.read_record(record) == []
    rows = [
        {"run": r, "step": s, "stays_right": k, "stays": 10, "turns_right": 10 - k, "turns": 10}
        for r in ("a", "b")
        for s, k in ((500, 0), (1000, 7))
    ]
    record.write_text("".join(json.dumps(r) + "\n" for r in rows))
    assert chunk_decision.read_record(record) == rows
    chunk_decision.plot(rows, tmp_path / "d.png")
    from PIL import Image

    assert Image.open(tmp_path / "d.png").size[0] > 400


def test_the_decision_probe_labels_the_place_by_the_pad_the_patch_names(bell_count_dataset):
    from lerobot_activearena.tasks.registry import get_task
    from lerobot_activearena.tasks.sampling import sample_scene

    probe = chunk_decision.decision_probe
    places = set()
    for seed in range(6):
        scene = sample_scene(get_task("check_block_color"), seed, "id")
        labels = probe.inspection_labels(scene)
        pads = sorted(
            (p["angle"], p["name"]) for p in scene.params["placements"] if p["category"] == "color_pad"
        )
        assert labels["colour"] == scene.params["patch_color"]
        assert pads[labels["pad"]][1] == f"{labels['colour']}_pad"
        assert labels["layout"] == ", ".join(n.replace("_", " ") for _, n in pads)
        places.add(labels["pad"])
    assert len(places) > 1  # the named pad's place varies with the scene
    with pytest.raises(SystemExit, match="reads one task's build"):  # the fixture holds two tasks
        probe.decision_frames(bell_count_dataset, None)


def test_the_decision_probe_scores_the_colour_a_think_first_span_names():
    named = chunk_decision.decision_probe.named_colours
    spans = [
        "<think>localize it; place on the red pad</think>",
        "<think>localize it</think>",
        "place on the blue pad",
    ]
    assert named(spans, np.array(["red", "red", "green"])) == "names the right colour in 33%, none in 33%"
    assert named(spans[:1], np.array(["red"])) == "names the right colour in 100%, none in 0%"
    places = chunk_decision.decision_probe.named_places
    placed = [
        "place on the red pad, the left one",
        "place on the red pad, the right one",
        "place on the red pad",
    ]
    assert places(placed, np.array([2, 2, 0])) == "names the right place in 33%, none in 33%"
    assert places(placed[:2], np.array([2, 0])) == "names the right place in 100%, none in 0%"
    layouts = chunk_decision.decision_probe.named_layouts
    laid = [
        "pick; blue pad right, green pad middle, red pad left; place on the red pad, the left one",
        "pick; red pad right, green pad middle, blue pad left; place on the red pad, the middle one",
        "pick; place on the red pad, the left one",
    ]
    truth = np.array(["blue pad, green pad, red pad"] * 3)
    assert layouts(laid, truth) == (
        "lists the pads right in 33%, none in 33%; the place follows its own list in 33%"
    )


def test_the_decision_probe_swaps_the_named_colour_for_the_next():
    swap = chunk_decision.decision_probe.swap_colour
    assert swap("localize the matching pad; place on the red pad") == (
        "localize the matching pad; place on the green pad"
    )
    assert swap("place on the green pad") == "place on the blue pad"
    assert swap("place on the blue pad") == "place on the red pad"
    assert swap("locate and pick up the gray target block") == "locate and pick up the gray target block"
    assert swap("place on the blue pad, the right one") == "place on the red pad, the middle one"
    assert swap("place on the red pad, the left one") == "place on the green pad, the right one"
