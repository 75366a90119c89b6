"""The asset library: every category builds in a scene, rests stably on the table, stays cheap to
render, randomises deterministically; pools are large enough; information labels render."""

import math

import mujoco
import numpy as np
import pytest

from lerobot_activearena.sim.assets import ASSETS, build_asset, categories
from lerobot_activearena.sim.assets.handheld import date_label_image
from lerobot_activearena.sim.look.dress import DRESS_GROUP
from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim

# Task-named categories the benchmark's tasks rely on (paper task inventory).
TASK_NAMED = [
    "hammer",
    "block",
    "bell",
    "stapler",
    "bottle",
    "switch",
    "pill_bottle",
    "mat",
    "color_pad",
    "rubiks_cube",
    "wooden_block",
    "coffee_box",
    "can",
    "plastic_box",
    "container",
    "plate",
    "cup",
    "coaster",
    "fan",
    "mouse",
    "bread_basket",
    "electronic_scale",
    "display_stand",
    "shoe",
    "seal",
    "button",
    "patch_block",
    "labeled_can",
]
# Objects that may roll (spheres, lying cylinders): tilt is not checked for these.
ROUND = {
    "apple",
    "orange",
    "tennis_ball",
    "ball",
    "lemon",
    "tomato",
    "pear",
    "lightbulb",
    "donut",
    "dice",
    "rolling_pin",
}
ALLOWED_COLLISION = {
    int(mujoco.mjtGeom.mjGEOM_BOX),
    int(mujoco.mjtGeom.mjGEOM_CYLINDER),
    int(mujoco.mjtGeom.mjGEOM_CAPSULE),
    int(mujoco.mjtGeom.mjGEOM_SPHERE),
    int(mujoco.mjtGeom.mjGEOM_ELLIPSOID),
    int(mujoco.mjtGeom.mjGEOM_MESH),
}


def test_pools_cover_the_tasks_and_enough_distractors():
    assert set(TASK_NAMED) <= set(categories("task"))
    assert len(categories("distractor")) >= 32
    task_families = {ASSETS[c].family for c in categories("task")}
    assert not task_families & {ASSETS[c].family for c in categories("distractor")}, (
        "a distractor shares a family with a task object"
    )


def _layout(builder, cats, margin=0.03):
    """Greedy non-overlapping placement over the fan (footprint discs plus ``margin``)."""
    placed, out = [], []
    cands = [(r, a) for r in np.arange(0.42, 1.0, 0.05) for a in np.arange(24.0, 157.0, 3.0)]
    for cat in cats:
        fp = ASSETS[cat].footprint
        for r, a in cands:
            xy = builder.workspace.place(r, a)[:2]
            if all(np.linalg.norm(xy - q) > fp + f + margin for q, f in placed):
                placed.append((xy, fp))
                out.append((cat, r, a))
                break
        else:
            raise AssertionError(f"no room for {cat}")
    return out


def _settle_scene(cats, steps=22):
    b = SceneBuilder()
    spawns = {}
    for k, (cat, r, a) in enumerate(_layout(b, cats)):
        info = b.add_object(cat, f"o_{cat}", r, a, yaw=0.7 * k, rng=np.random.default_rng(k))
        spawns[info.name] = (b.workspace.place(r, a) + [0, 0, 0.0005], cat)
    model, info = b.compile()
    sim = ActiveArenaSim(model, info)
    for _ in range(steps):  # 22 control steps at 15 Hz: ~1.5 s
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
        assert min(info.half_extents) > 0 and 0.02 <= info.mass <= 1.0, cat


def test_static_assets_build_in_a_scene_without_a_free_joint():
    cats = [c for c in ASSETS if ASSETS[c].static]
    b = SceneBuilder()
    infos = [b.add_object(cat, f"s_{cat}", r, a) for cat, r, a in _layout(b, cats)]
    model, _ = b.compile()
    for info in infos:
        assert min(info.half_extents) > 0, info.category
        for j in np.flatnonzero(model.jnt_bodyid == model.body(info.body).id):
            assert model.jnt_type[j] != mujoco.mjtJoint.mjJNT_FREE, info.category


def test_geometry_is_cheap_and_collision_shapes_are_simple():
    spec = mujoco.MjSpec()
    for k, cat in enumerate(sorted(ASSETS)):
        build_asset(spec, cat, f"g_{cat}", (0.3 * (k % 10), 0.3 * (k // 10), 0))
    model = spec.compile()
    colliding = (model.geom_contype != 0) | (model.geom_conaffinity != 0)
    meshes = model.geom_type == mujoco.mjtGeom.mjGEOM_MESH
    assert np.all(model.mesh_vertnum[model.geom_dataid[meshes & colliding]] < 200), (
        "collision meshes stay coarse"
    )
    # Drawn-only looks (sim/look/dress.py) may be finer, within a render budget per object.
    drawn = meshes & (model.geom_group == DRESS_GROUP)
    triangles = np.bincount(
        model.geom_bodyid[drawn], model.mesh_facenum[model.geom_dataid[drawn]], model.nbody
    )
    assert drawn.any() and triangles.max() <= 2500, f"{triangles.max()} drawn triangles on one object"
    assert set(model.geom_type[colliding].tolist()) <= ALLOWED_COLLISION
    per_object = np.bincount(model.geom_bodyid, minlength=model.nbody)
    assert per_object.max() <= 16, "too many geoms on one object"


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
        b.add_object(
            "labeled_can", "can", 0.42, 90.0, yaw=math.radians(270.0), date=date
        )  # label faces the robot
        model, info = b.compile()
        sim = ActiveArenaSim(model, info)
        a = sim.home_action()
        a[17] = 0.75
        for _ in range(12):
            sim.step(a)
        v = sim.visibility()
        assert v.visible[0]
        u, w = (v.uv_norm[0] * [512, 384]).astype(int)
        crops.append(sim.render_head()[w - 25 : w + 25, u - 15 : u + 15].astype(int))
    assert np.abs(crops[0] - crops[1]).sum() > 0, "different dates must render differently"


def test_asset_sheet_cli_renders_a_labelled_grid(tmp_path):
    from PIL import Image

    from lerobot_activearena.cli.asset_sheet import THUMB, main

    out = tmp_path / "sheet.png"
    main(["--categories", "hammer,apple,bell", "--out", str(out), "--columns", "2", "--zoom", "2"])
    img = np.asarray(Image.open(out))
    assert img.shape == (2 * THUMB[1], 2 * THUMB[0], 3)
    assert img[: THUMB[1], : THUMB[0]].std() > 5, "thumbnail is blank"
    with pytest.raises(SystemExit, match="unknown categories"):
        main(["--categories", "hammer,unicorn", "--out", str(out)])


def test_arc_labels_read_left_to_right_from_outside():
    """Texture u must grow to the viewer's right (+y for a viewer on +x looking at the can), and the
    faces must face outward: a mirrored date would be unreadable."""
    spec = mujoco.MjSpec()
    build_asset(spec, "labeled_can", "can", (0.4, 0, 0.74), date="2024-06-17")
    mesh = spec.mesh("can_label_mesh")
    verts = np.asarray(mesh.uservert).reshape(-1, 3)
    uv = np.asarray(mesh.usertexcoord).reshape(-1, 2)
    assert np.corrcoef(verts[:, 1], uv[:, 0])[0, 1] > 0.99
    for f in np.asarray(mesh.userface).reshape(-1, 3):
        a, b, c = verts[f]
        normal = np.cross(b - a, c - a)
        assert normal @ np.array([a[0], a[1], 0.0]) > 0  # counter-clockwise seen from outside


def test_mat_text_is_printed_only_when_asked():
    spec = mujoco.MjSpec()
    plain = build_asset(spec, "mat", "plain", (0.4, 0, 0.74), color_name="red")
    printed = build_asset(spec, "mat", "printed", (0.4, 0.2, 0.74), color_name="green", text="VALID")
    model = spec.compile()
    names = {model.geom(i).name for i in range(model.ngeom)}
    assert "printed_text" in names and "plain_text" not in names
    assert (plain.attributes["text"], printed.attributes["text"]) == ("", "VALID")
