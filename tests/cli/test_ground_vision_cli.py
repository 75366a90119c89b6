"""`activearena-ground-vision`: a from-scratch backbone's vision tower learns where the focus object is
in a build's head frames, and the grounded model loads as a ``--policy.vlm_path``."""

import json

import numpy as np
import pytest
import torch
from helpers.params import DATASET_REPO
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from safetensors.torch import load_file

from lerobot_activearena.cli.ground_vision import main as ground_main
from lerobot_activearena.cli.slim_dataset import main as slim_main
from lerobot_activearena.policies.activearena_vla.vision_grounding import (
    READING,
    GroundingOutput,
    appearance_class,
    check_decoded_size,
    color_jitter,
    grounding_loss,
    identity_token_targets,
    load_grounding_frames,
    random_convolution,
    reading_rows,
    search_target_points,
    search_token_targets,
    token_cells,
    within_cells,
)


def outputs(logits, points, search=None, count=None, identity=None):
    n, t = points.shape[:2]
    search = torch.zeros(n, t) if search is None else search
    count = torch.zeros(n, 2) if count is None else count
    identity = torch.zeros(n, t, 1) if identity is None else identity
    return [GroundingOutput(logits, points, search, count, identity)]


def test_token_cells_name_the_merged_token_under_the_object_or_none():
    visible = np.array([True, True, True, False])
    uv = np.array([[0.1, 0.9], [0.99, 0.01], [0.5, 0.5], [-1.0, -1.0]])
    # a 3 x 4 grid: (u 0.1, v 0.9) is row 2, column 0; (0.99, 0.01) row 0, column 3; the centre row 1,
    # column 2; not visible is the 13th class
    np.testing.assert_array_equal(token_cells(visible, uv, 3, 4), [8, 3, 6, 12])


def test_within_cells_place_the_point_inside_its_token():
    uv = np.array([[0.1, 0.9], [1.0, 0.0], [0.5, 0.5]])
    # 3 x 4 grid: u 0.1 -> 0.4 columns in, v 0.9 -> 2.7 rows (0.7 into row 2); u 1.0 is the far edge of
    # the last column
    np.testing.assert_allclose(within_cells(uv, 3, 4), [[0.4, 0.7], [1.0, 0.0], [0.0, 0.5]], atol=1e-6)


def test_grounding_loss_fits_the_point_only_in_the_objects_token():
    cells = torch.tensor([1, 2])  # two tokens + "not in view": frame 0 shows the object in token 1
    within = torch.tensor([[0.25, 0.75], [0.0, 0.0]])
    logits = torch.tensor([[0.0, 5.0, 0.0], [0.0, 0.0, 5.0]])
    points = torch.full((2, 2, 2), 0.5)
    base = grounding_loss(outputs(logits, points), cells, within, point_weight=0.0)
    assert torch.isclose(base, torch.nn.functional.cross_entropy(logits, cells))
    weighted = grounding_loss(outputs(logits, points), cells, within, point_weight=2.0)
    assert torch.isclose(weighted - base, torch.tensor(2.0 * 0.25))  # |0.5 - 0.25|, |0.5 - 0.75|
    elsewhere = points.clone()
    elsewhere[0, 0] = 0.0  # another token of the same frame, and the frame without the object
    elsewhere[1] = 0.9
    assert torch.isclose(grounding_loss(outputs(logits, elsewhere), cells, within, 2.0), weighted)
    exact = points.clone()
    exact[0, 1] = within[0]
    assert torch.isclose(grounding_loss(outputs(logits, exact), cells, within, 2.0), base)


def test_search_targets_are_the_searched_objects_in_view_that_the_task_needs():
    # three objects: 0 a block to count, 1 a distractor (searched for, not needed), 2 the button
    object_uv = np.array([[0.1, 0.2, 0.5, 0.5, 0.9, 0.9], [0.1, 0.2, -1, -1, 0.9, 0.9]])
    visible = np.array([[1, 1, 1], [1, 0, 1]])
    searched = np.array([[1, 1, 0], [0, 0, 1]])  # frame 0 counts, frame 1 presses
    points = search_target_points(object_uv, visible, searched, [np.array([0, 2])] * 2)
    np.testing.assert_allclose(points[0], [[0.1, 0.2], [-1, -1], [-1, -1]])
    np.testing.assert_allclose(points[1], [[-1, -1], [-1, -1], [0.9, 0.9]])


def test_search_token_targets_mark_each_targets_token_and_count_them():
    points = np.array(
        [
            [[0.1, 0.1], [0.15, 0.2], [0.9, 0.9]],  # two in token 0 (a 2 x 2 grid), one in token 3
            [[-1, -1], [-1, -1], [-1, -1]],
        ],
        np.float32,
    )
    occupied, count = search_token_targets(points, 2, 2)
    np.testing.assert_array_equal(occupied, [[1, 0, 0, 1], [0, 0, 0, 0]])
    np.testing.assert_array_equal(count, [3, 0])


def test_grounding_loss_adds_the_search_terms_with_their_weight():
    cells = torch.tensor([2])
    logits, points = torch.tensor([[0.0, 0.0, 3.0]]), torch.full((1, 2, 2), 0.5)
    search, count = torch.tensor([[2.0, -1.0]]), torch.tensor([[0.0, 1.0, 0.0]])
    out = outputs(logits, points, search, count)
    occupied, number = torch.tensor([[1.0, 0.0]]), torch.tensor([1])
    base = grounding_loss(out, cells, None, 0.0)
    both = grounding_loss(out, cells, None, 0.0, (occupied, number), 0.5)
    bce = torch.nn.functional.binary_cross_entropy_with_logits(search, occupied)
    ce = torch.nn.functional.cross_entropy(count, number)
    assert torch.isclose(both - base, 0.5 * (bce + ce))
    wrong = grounding_loss(out, cells, None, 0.0, (occupied, torch.tensor([2])), 0.5)
    assert wrong > both  # the count is read


def test_appearance_classes_drop_instance_numbers_and_keep_shown_ones():
    assert appearance_class("green_block_1", "green block 2") == "green block"
    assert appearance_class("green_block_0", "green block 1") == "green block"
    assert appearance_class("button_2", "button 2") == "button 2"  # the number is on the button
    assert appearance_class("red_block_0", "red block") == "red block"
    assert appearance_class("bell", "bell") == "bell"


def test_identity_token_targets_mark_each_class_in_its_token():
    uv = np.array([[[0.1, 0.1], [0.15, 0.2], [0.9, 0.9]]], np.float32)
    classes = np.array([[0, 0, 1]])  # two of class 0 in token 0 (a 2 x 2 grid), one of class 1 in token 3
    out = identity_token_targets(uv, classes, 3, 2, 2)
    np.testing.assert_array_equal(out[0], [[1, 0, 0], [0, 0, 0], [0, 0, 0], [0, 1, 0]])
    hidden = identity_token_targets(uv, np.array([[-1, -1, 2]]), 3, 2, 2)
    np.testing.assert_array_equal(hidden[0].sum(0), [0, 0, 1])


def test_grounding_loss_names_the_class_of_tokens_that_hold_one():
    cells = torch.tensor([2])
    logits, points = torch.tensor([[0.0, 0.0, 3.0]]), torch.full((1, 3, 2), 0.5)
    guess = torch.tensor([[[2.0, -2.0], [-1.0, 0.5], [5.0, -5.0]]])
    # token 0 holds class 0, token 1 class 1, token 2 both (not scored)
    truth = torch.tensor([[[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]])
    out = outputs(logits, points, identity=guess)
    base = grounding_loss(out, cells, None, 0.0)
    both = grounding_loss(out, cells, None, 0.0, identity=truth, identity_weight=2.0)
    ce = torch.nn.functional.cross_entropy(guess[0, :2], torch.tensor([0, 1]))
    assert torch.isclose(both - base, 2.0 * ce)
    swapped = truth[..., [1, 0]]
    assert grounding_loss(out, cells, None, 0.0, identity=swapped, identity_weight=2.0) > both


def test_grounding_frames_are_the_datasets_frames_and_annotations(bell_count_dataset):
    frames = load_grounding_frames(bell_count_dataset)
    ds = LeRobotDataset(DATASET_REPO, root=bell_count_dataset)
    assert len(frames.images) == ds.num_frames == len(frames.visible)
    assert frames.visible.any() and not frames.visible.all()
    for i in (0, ds.num_frames // 3, ds.num_frames - 1):
        item = ds[i]
        at = np.flatnonzero(
            (frames.episodes == int(item["episode_index"])) & (frames.frames == int(item["frame_index"]))
        )
        assert len(at) == 1
        image = (item["observation.images.head"] * 255).round().to(torch.uint8)
        assert (frames.images[at[0]].int() - image.int()).abs().max() <= 1
        assert frames.visible[at[0]] == bool(item["focus_object_visible"])
        np.testing.assert_allclose(frames.uv[at[0]], item["target_uv_norm"].numpy())
    searched = load_grounding_frames(bell_count_dataset, search=True).search_uv
    assert searched.shape == (len(frames.images), 16, 2)
    # the focus object, where it is a search target, is one of them; the count task's counting frames
    # (no focus object) still show some
    assert (searched[..., 0] >= 0).any(1)[frames.visible].mean() > 0.5
    assert (searched[..., 0] >= 0).any(1)[~frames.visible].any()
    named = load_grounding_frames(bell_count_dataset, identity=True)
    assert "bell" in named.classes and "button 1" in named.classes and "green block" in named.classes
    assert not any(c[-1].isdigit() for c in named.classes if "block" in c)
    # a class wherever the object is visible, nowhere else
    assert ((named.object_class >= 0) == (named.object_uv[..., 0] >= 0)).all()


def test_grounding_on_a_subset_decodes_only_its_episodes(bell_count_dataset):
    whole = load_grounding_frames(bell_count_dataset)
    one = load_grounding_frames(bell_count_dataset, episodes=[1])
    assert set(one.episodes) == {1} and len(one.images) == (whole.episodes == 1).sum() < len(whole.images)
    assert torch.equal(one.images, whole.images[whole.episodes == 1])
    with pytest.raises(ValueError, match="no episode 7 .*--episodes"):
        load_grounding_frames(bell_count_dataset, episodes=[0, 7])


def test_a_build_too_large_to_decode_is_refused_with_the_subset_that_fits():
    check_decoded_size(1000, (192, 256, 3), "small")  # 0.3 GB: decoded
    with pytest.raises(ValueError, match=r"10000000 frames .*\(--episodes 0-N, about \d+ frames fit"):
        check_decoded_size(10_000_000, (192, 256, 3), "huge")


def test_reading_rows_are_the_frames_near_each_reading_in_its_episode():
    episodes = np.array([0, 0, 0, 0, 0, 1, 1, 1])
    frames = np.array([0, 1, 2, 3, 4, 0, 1, 2])
    inspections = {
        0: [{"object": "gray_block", "frame": 2, "reading": "green"}],
        1: [
            {"object": "cola_can", "frame": 0, "reading": {"label_color": "red"}},
            {"object": "x", "frame": 1},
        ],
    }
    rows = reading_rows(episodes, frames, inspections, window=1)
    assert len(rows) == 2  # an inspection without a reading names nothing
    np.testing.assert_array_equal(rows[0][0], [1, 2, 3])
    assert rows[0][1:] == ("gray_block", "green")
    np.testing.assert_array_equal(rows[1][0], [5, 6])  # the window stops at its episode's frames
    assert rows[1][1:] == ("cola_can", "red")


def test_a_reading_window_names_the_inspected_object_by_what_it_shows(bell_count_dataset, tmp_path):
    """On a copy of the build whose bell episode says the expert read the bell at a frame that shows it,
    the bell is "bell showing gold" where visible within the window and "bell" elsewhere; nothing else
    is renamed; a build without readings is refused."""
    import shutil

    with pytest.raises(ValueError, match="no expert readings"):
        load_grounding_frames(bell_count_dataset, identity=True, reading_window=3)
    root = tmp_path / "read"
    shutil.copytree(bell_count_dataset, root)
    plain = load_grounding_frames(root, identity=True)
    for path in sorted((root / "meta/activearena/sidecars").glob("episode_*.json")):
        side = json.loads(path.read_text())
        bells = [o for o in side["objects"] if o["key"] == "bell"]
        if bells:
            episode, slot = int(path.stem.split("_")[1]), bells[0]["index"]
            shows = np.flatnonzero((plain.episodes == episode) & (plain.object_class[:, slot] >= 0))
            read_at = int(plain.frames[shows[len(shows) // 2]])
            side.setdefault("expert_notes", {})["inspections"] = [
                {"object": "bell", "frame": read_at, "reading": "gold"}
            ]
            path.write_text(json.dumps(side))
    named = load_grounding_frames(root, identity=True, reading_window=3)
    shown = named.classes.index(f"bell{READING}gold")
    near = (named.episodes == episode) & (np.abs(named.frames - read_at) <= 3)
    seen = named.object_class[:, slot] >= 0
    assert (seen & near).any()
    assert (named.object_class[near & seen, slot] == shown).all()
    assert (named.object_class[~near, slot] != shown).all()
    bell = named.classes.index("bell")
    assert (named.object_class[~near & seen & (named.episodes == episode), slot] == bell).all()
    others = [k for k in range(named.object_class.shape[1]) if k != slot]  # nothing else renamed
    rename = {plain.classes.index(c): named.classes.index(c) for c in plain.classes}
    before = plain.object_class[:, others]
    assert (
        np.where(before >= 0, np.vectorize(lambda c: rename.get(c, -1))(before), -1)
        == named.object_class[:, others]
    ).all()


def test_ground_vision_fits_the_tower_and_keeps_the_language_model(
    bell_count_dataset, tiny_vlm, tmp_path, capsys
):
    out = tmp_path / "grounded"
    args = [str(tiny_vlm), "--root", str(bell_count_dataset), "--out", str(out), "--val-every", "2"]
    fit = [
        "--epochs",
        "3",
        "--batch-size",
        "32",
        "--lr",
        "1e-3",
        "--point-weight",
        "1",
        "--search-weight",
        "1",
        "--identity-weight",
        "1",
    ]
    ground_main([*args, *fit])
    printed = capsys.readouterr().out
    assert "search targets in view counted right" in printed and "objects named right" in printed
    report = json.loads((out / "grounding.json").read_text())
    assert report["grid"] == [3, 4] and report["held_out_episodes"] == [1]
    assert report["point_weight"] == 1.0 and report["search_weight"] == 1.0
    assert report["identity_weight"] == 1.0 and "bell" in report["classes"]
    for epoch in report["history"]:
        assert 0 <= epoch["search_count_accuracy"] <= 1 and 0 < epoch["search_count_majority"] <= 1
        assert 0 <= epoch["identity_accuracy"] <= 1 and 0 < epoch["identity_majority"] <= 1
    info = json.loads((bell_count_dataset / "meta/info.json").read_text())
    h, w = info["features"]["observation.images.head"]["shape"][:2]
    half_diagonal = 0.5 * np.hypot(h / 3, w / 4)  # a token's centre is no farther from a point in it
    for epoch in report["history"]:
        assert 0 <= epoch["median_centre_error_px"] <= half_diagonal
        assert 0 <= epoch["median_point_error_px"] <= 2 * half_diagonal
    losses = [h["train_loss"] for h in report["history"]]
    assert len(losses) == 3 and losses[-1] < losses[0]
    before, after = load_file(tiny_vlm / "model.safetensors"), load_file(out / "model.safetensors")
    assert before.keys() == after.keys()
    vision = [k for k in before if ".visual." in k]
    assert vision and all(not torch.equal(before[k], after[k]) for k in vision if k.endswith("weight"))
    assert all(torch.equal(before[k], after[k]) for k in before if ".language_model." in k)
    from transformers import AutoProcessor, Qwen3VLForConditionalGeneration

    Qwen3VLForConditionalGeneration.from_pretrained(out)
    AutoProcessor.from_pretrained(out)

    with pytest.raises(SystemExit):  # an existing model is never replaced silently
        ground_main(args)


def test_ground_vision_refuses_a_build_without_annotations(bell_count_dataset, tiny_vlm, tmp_path, capsys):
    slim = tmp_path / "slim"
    slim_main(["--root", str(bell_count_dataset), "--out", str(slim)])
    with pytest.raises(SystemExit):
        ground_main([str(tiny_vlm), "--root", str(slim), "--out", str(tmp_path / "g")])
    assert "full build" in capsys.readouterr().err
    assert not (tmp_path / "g").exists()
    with pytest.raises(SystemExit):
        ground_main(
            [
                str(tiny_vlm),
                "--root",
                str(bell_count_dataset),
                "--out",
                str(tmp_path / "g"),
                "--reading-window",
                "4",
            ]
        )
    assert "needs --identity-weight" in capsys.readouterr().err
    assert not (tmp_path / "g").exists()


def test_color_jitter_changes_each_frames_colours_and_nothing_else():
    torch.manual_seed(0)
    frame = torch.zeros(3, 24, 32, dtype=torch.uint8)
    frame[:, 8:16, 10:20] = torch.tensor([200, 40, 40], dtype=torch.uint8)[:, None, None]  # a red patch
    images = torch.stack([frame, frame, frame])
    out = color_jitter(images)
    assert out.shape == images.shape and out.dtype == torch.uint8
    assert not torch.equal(out[0], out[1])  # each frame its own jitter
    for image in out:  # the patch stays where it was: the annotations still hold
        inside = image[:, 8:16, 10:20].float().mean()
        assert inside > image[:, :8].float().mean() + 20


def test_random_convolution_retextures_some_frames_and_keeps_their_shapes():
    torch.manual_seed(0)
    frame = torch.full((3, 24, 32), 60, dtype=torch.uint8)
    frame[:, 8:16, 10:20] = torch.tensor([200, 40, 40], dtype=torch.uint8)[:, None, None]  # a red patch
    images = frame.expand(8, -1, -1, -1).contiguous()
    assert torch.equal(random_convolution(images, p=0.0), images)
    out = random_convolution(images, p=1.0)
    assert out.shape == images.shape and out.dtype == torch.uint8
    assert all(not torch.equal(o, frame) for o in out) and not torch.equal(out[0], out[1])
    for image in out:  # the patch is still one colour, another than the table's, where it was
        patch, table = image[:, 11:13, 13:17].flatten(1), image[:, 19:21, 3:8].flatten(1)
        assert (patch == patch[:, :1]).all() and (table == table[:, :1]).all()
        assert not torch.equal(patch[:, 0], table[:, 0])
    mixed = random_convolution(images, p=0.5)
    kept = sum(torch.equal(m, frame) for m in mixed)
    assert 0 < kept < len(images)


def test_ground_vision_augments_and_scores_another_build(bell_count_dataset, tiny_vlm, tmp_path, capsys):
    out = tmp_path / "grounded"
    args = [str(tiny_vlm), "--root", str(bell_count_dataset), "--out", str(out), "--val-every", "2"]
    ground_main(
        [
            *args,
            "--epochs",
            "1",
            "--batch-size",
            "32",
            "--jitter",
            "--random-conv",
            "--eval-root",
            str(bell_count_dataset),
        ]
    )
    assert f"{bell_count_dataset}: in view or not" in capsys.readouterr().out
    report = json.loads((out / "grounding.json").read_text())
    assert (
        report["jitter"]["hue"] == [-0.1, 0.1]
        and report["random_conv"]
        and report["eval_root"] == str(bell_count_dataset)
    )
    last = report["history"][-1]
    everything = LeRobotDataset(DATASET_REPO, root=bell_count_dataset).num_frames
    assert last["eval_frames"] == everything > last["frames"]  # the whole other build, not its held-out part
    assert 0 <= last["eval_in_view_accuracy"] <= 1
    with pytest.raises(SystemExit):
        ground_main([*args, "--overwrite", "--eval-root", str(tmp_path / "nothing")])
    assert "is not a LeRobot dataset" in capsys.readouterr().err
