"""The asset library: every category builds, rests stably on the table, randomises
deterministically; pools are large enough; information labels render."""

import math

import mujoco
import numpy as np
import pytest

from lerobot_activearena.sim.assets import ASSETS, build_asset, categories
from lerobot_activearena.sim.assets.task_objects import date_label_image
from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim

TASK_NAMED = ["hammer", "block", "bell", "stapler", "bottle", "switch", "pill_bottle", "mat", "color_pad",
              "rubiks_cube", "wooden_block", "coffee_box", "can", "plastic_box", "container", "plate", "cup",
              "coaster", "fan", "mouse", "bread_basket", "electronic_scale", "display_stand", "shoe", "seal",
              "button", "patch_block", "labeled_can"]
ROUND = {"apple", "orange", "tennis_ball", "ball", "lemon", "tomato", "pear", "lightbulb", "donut", "dice"}


def test_pools_cover_the_tasks_and_enough_distractors():
    assert set(TASK_NAMED) <= set(categories("task"))
    assert len(categories("distractor")) >= 30
    task_families = {ASSETS[c].family for c in categories("task")}
    assert not task_families & {ASSETS[c].family for c in categories("distractor")}, \
        "a distractor shares a family with a task object"


def _settle_scene(cats):
    b = SceneBuilder()
    spawns = {}
    for k, cat in enumerate(cats):
        r, a = (0.45, 0.7, 0.95)[k % 3], 25 + (k // 3) * (130 / max(1, (len(cats) - 1) // 3))
        info = b.add_object(cat, f"o_{cat}", r, a, yaw=0.3 * k, rng=np.random.default_rng(k))
        spawns[info.name] = (b.workspace.place(r, a), cat)
    model, info = b.compile()
    sim = ActiveArenaSim(model, info)
    for _ in range(22):  # ~1.5 s
        sim.step(sim.home_action())
    return sim, spawns


@pytest.mark.parametrize("chunk", range(3))
def test_every_free_object_rests_stably_on_the_table(chunk):
    cats = sorted(c for c in ASSETS if not ASSETS[c].static)[chunk::3]
    sim, spawns = _settle_scene(cats)
    for name, (spawn, cat) in spawns.items():
        body = sim.data.body(name)
        assert np.isfinite(body.xpos).all()
        assert np.linalg.norm(body.xpos[:2] - spawn[:2]) < 0.02, f"{cat} slid or rolled away"
        assert abs(body.xpos[2] - spawn[2]) < 0.01, f"{cat} sank or jumped (dz={body.xpos[2] - spawn[2]:.3f})"
        if cat not in ROUND:
            tilt = math.degrees(math.acos(np.clip(body.xmat.reshape(3, 3)[2, 2], -1, 1)))
            assert tilt < 20, f"{cat} tipped over by {tilt:.0f} deg"
        info = next(o for o in sim.info.objects if o.name == name)
        assert min(info.half_extents) > 0 and info.mass > 0


def test_static_assets_compile_and_have_no_free_joint():
    for cat in [c for c in ASSETS if ASSETS[c].static]:
        spec = mujoco.MjSpec()
        build_asset(spec, cat, f"s_{cat}", (0, 0, 0))
        m = spec.compile()
        assert all(m.jnt_type[j] != mujoco.mjtJoint.mjJNT_FREE for j in range(m.njnt)), cat


def test_randomisation_is_deterministic_per_seed():
    for cat, entry in ASSETS.items():
        if entry.randomize is None:
            continue
        a = entry.randomize(np.random.default_rng(3))
        b = entry.randomize(np.random.default_rng(3))
        assert a == b, cat


def test_unknown_category_and_bad_parameters_are_clear_errors():
    spec = mujoco.MjSpec()
    with pytest.raises(ValueError, match="unknown asset category 'unicorn'"):
        build_asset(spec, "unicorn", "u", (0, 0, 0))
    with pytest.raises(ValueError, match="unknown mat colour"):
        build_asset(spec, "mat", "m", (0, 0, 0), color_name="plaid")
    with pytest.raises(ValueError, match="label_kind"):
        build_asset(spec, "labeled_can", "c", (0, 0, 0), label_kind="barcode")


def test_date_labels_differ_and_render_on_the_can():
    assert not np.array_equal(date_label_image("2024-05-17"), date_label_image("2025-05-17"))
    crops = []
    for date in ("2023-01-01", "2026-12-31"):
        b = SceneBuilder()
        b.add_object("labeled_can", "can", 0.42, 90.0, yaw=math.radians(270.0), date=date)  # label faces the robot
        model, info = b.compile()
        sim = ActiveArenaSim(model, info)
        a = sim.home_action()
        a[17] = 0.75
        for _ in range(12):
            sim.step(a)
        v = sim.visibility()
        assert v.visible[0]
        u, w = (v.uv_norm[0] * [512, 384]).astype(int)
        crops.append(sim.render_head()[w - 25: w + 25, u - 15: u + 15].astype(int))
    assert np.abs(crops[0] - crops[1]).sum() > 0, "different dates must render differently"


def test_asset_sheet_cli_renders_a_labelled_grid(tmp_path):
    from PIL import Image

    from lerobot_activearena.cli.asset_sheet import THUMB, main

    out = tmp_path / "sheet.png"
    main(["--categories", "hammer,apple,bell", "--out", str(out), "--columns", "2"])
    img = Image.open(out)
    assert img.size == (2 * THUMB[0], 2 * THUMB[1])
    with pytest.raises(SystemExit, match="unknown categories"):
        main(["--categories", "hammer,unicorn", "--out", str(out)])
