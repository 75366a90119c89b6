"""Dressed looks (code-built meshes drawn in place of primitives): inside the collision extents, and
never changing what physics or perception see."""

import hashlib

import mujoco
import numpy as np
import pytest

from lerobot_activearena.episodes.rollout import run_expert_episode
from lerobot_activearena.sim.assets import ASSETS, devices, handheld, parts, primitives, surfaces
from lerobot_activearena.sim.look.dress import DRESS_GROUP, SHAPE_GROUP
from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.tasks import get_task
from lerobot_activearena.tasks.sampling import sample_scene

TOLERANCE_M = 0.001  # how far a drawn vertex may stand outside the collision shapes' bounding box


def _subtree(model, root: int) -> np.ndarray:
    bodies = [b for b in range(model.nbody) if model.body_rootid[b] == root or b == root]
    return np.flatnonzero(np.isin(model.geom_bodyid, bodies))


def _corners(model, data, g) -> np.ndarray:
    center, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
    box = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * half + center
    return data.geom_xpos[g] + box @ data.geom_xmat[g].reshape(3, 3).T


def test_every_dressed_part_stays_inside_its_objects_collision_extents():
    dressed = []
    for category in sorted(ASSETS):
        builder = SceneBuilder()
        builder.add_object_at(category, "thing", (0.0, 0.6, 0.8))
        model, _ = builder.compile()
        data = mujoco.MjData(model)
        mujoco.mj_forward(model, data)
        geoms = _subtree(model, model.body("thing").id)
        drawn = [g for g in geoms if model.geom_group[g] == DRESS_GROUP]
        if not drawn:
            continue
        dressed.append(category)
        solid = [g for g in geoms if model.geom_contype[g] or model.geom_conaffinity[g]]
        pts = np.concatenate([_corners(model, data, g) for g in solid])
        lo, hi = pts.min(axis=0) - TOLERANCE_M, pts.max(axis=0) + TOLERANCE_M
        for g in drawn:
            assert model.geom_contype[g] == 0 and model.geom_conaffinity[g] == 0
            mesh = model.geom_dataid[g]
            verts = model.mesh_vert[
                model.mesh_vertadr[mesh] : model.mesh_vertadr[mesh] + model.mesh_vertnum[mesh]
            ]
            world = data.geom_xpos[g] + verts @ data.geom_xmat[g].reshape(3, 3).T
            out = np.maximum(lo - world, world - hi).max()
            assert out <= 0, (
                f"{category}: {model.geom(g).name} reaches {out * 1000:.1f} mm past its collision box"
            )
        assert any(model.geom_group[g] == SHAPE_GROUP for g in geoms), f"{category}: no primitive was hidden"
    assert {
        "bell",
        "cup",
        "can",
        "bottle",
        "plate",
        "pill_bottle",
        "mouse",
        "shoe",
        "seal",
        "coaster",
        "button",
        "switch",
        "electronic_scale",
        "hammer",
        "stapler",
        "fan",
        "mat",
        "color_pad",
        "plastic_box",
        "bread_basket",
        "container",
        # clutter (assets/dressing_clutter.py)
        "candle",
        "chess_pawn",
        "pepper_grinder",
        "kettle",
        "trophy",
        "flower_pot",
        "cactus",
        "lightbulb",
        "pear",
        "teapot",
        "tape_roll",
        "book",
        "sponge",
        "tissue_box",
    } <= set(dressed)


def _undressed(monkeypatch):
    for module in (primitives, parts, devices, handheld, surfaces):
        monkeypatch.setattr(module, "dress", lambda *args, **kwargs: None)


def _episode(task, seed):
    r = run_expert_episode(task, seed, "id")
    h = hashlib.sha256(r.actions.tobytes())
    for f in r.frames:
        for k in sorted(f):
            h.update(np.ascontiguousarray(f[k]).tobytes())
    return r.success, h.hexdigest()


@pytest.mark.parametrize(
    "task",
    [
        "click_bell_rotate_view",  # bell
        "place_empty_cup_rotate_view",  # cup, coaster
        "place_container_plate_rotate_view",  # plate
        "place_shoe_rotate_view",  # shoe
        "stamp_seal_rotate_view",  # seal
        "count_target_press_button",  # buttons
        "turn_switch_rotate_view",  # switch (a dressed hinged part)
    ],
)
def test_a_dressed_look_changes_no_state_action_or_annotation(task, monkeypatch):
    """The expert's episode (states, actions, every annotation, visibility included) is
    bit-identical with the meshes drawn or the primitives drawn instead."""
    meshes = np.sum(sample_scene(get_task(task), 0, "id").model.geom_group == DRESS_GROUP)
    dressed = _episode(task, 0)
    _undressed(monkeypatch)
    assert meshes > 0 and np.sum(sample_scene(get_task(task), 0, "id").model.geom_group == DRESS_GROUP) == 0
    plain = _episode(task, 0)
    assert dressed == plain and dressed[0]
