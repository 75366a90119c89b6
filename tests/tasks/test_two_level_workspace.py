"""The two-level workspace as a task property: per-level placement, clearance and clutter, the
column, the upper band's reach limits, the search views pitched up, and depth-aware visibility
through the upper slab and the column (on compiled scenes)."""

import math

import mujoco
import numpy as np
import pytest

from lerobot_activearena.expert.kinematics import side_reachable
from lerobot_activearena.sim.action import TORSO_YAW
from lerobot_activearena.sim.head_camera import SEARCH_PITCH, SEARCH_VIEWS, UPPER_SEARCH_PITCH, search_views
from lerobot_activearena.sim.workspace import UPPER_TOP, fan_workspace, two_level_workspace
from lerobot_activearena.tasks.base import Subtask, Task
from lerobot_activearena.tasks.draft import (
    HIDDEN,
    TWO_LEVEL_CLUTTER,
    TWO_LEVEL_LOWER_CLUTTER_R,
    UPPER_REACH_R,
    Region,
    SamplingError,
    SceneDraft,
)
from lerobot_activearena.tasks.sampling import principle_violations, sample_scene, sector_visibility

UPPER = Region(level=1)


def _draft(split="id", seed=0):
    return SceneDraft(split, np.random.default_rng(seed), "two_level")


def _z(model, name):
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    return data.body(name).xpos[2]


def test_regions_place_on_their_level_and_clearance_is_per_level():
    d = _draft()
    assert d.workspace.two_level and UPPER.r == UPPER_REACH_R and Region().r != UPPER.r
    _, r_up, a_up = d.place("block", "up", "block", UPPER)
    assert UPPER_REACH_R[0] <= r_up <= UPPER_REACH_R[1]
    # the same spot on the lower fan is free (another level), on the upper band it is taken
    d.place("block", "low", "block", Region(r=(0.45, 0.45)), r=0.45, angle=a_up)
    with pytest.raises(SamplingError):
        d.place("block", "up2", "block", UPPER, r=r_up, angle=a_up, tries=3)
    model, _ = d.builder.compile()
    assert _z(model, "up") > UPPER_TOP and _z(model, "low") < UPPER_TOP - 0.2
    assert [p.get("level") for p in d.placements] == [1, 0]
    with pytest.raises(ValueError, match="level must be 0"):
        Region(level=2)


def test_the_column_and_the_band_edges_are_kept_clear():
    d = _draft()
    with pytest.raises(SamplingError):  # the column stands at r 0.775 straight ahead
        d.place("block", "on_column", "block", Region(r=(0.775, 0.775)), angle=90.0, tries=5)
    with pytest.raises(SamplingError):  # a block's footprint would hang over the band's outer edge
        d.place("block", "edge", "block", UPPER, r=0.79, angle=60.0, tries=5)
    with pytest.raises(ValueError, match="level 1"):  # a one-level task has no upper band
        SceneDraft("id", np.random.default_rng(0)).place("block", "b", "block", UPPER)


def test_an_oblong_object_fits_the_band_by_its_radial_reach():
    """The bread basket's footprint circle (11 cm) does not fit the 20 cm band at 0.70 m; along the
    radius its long side reaches 9.9 cm either way (give or take its yaw), which does."""
    from lerobot_activearena.tasks.inventory.place_object_basket_fan_double import BASKET_HALF_DEPTH

    d = _draft()
    with pytest.raises(SamplingError):
        d.place("bread_basket", "b", "bread basket", UPPER, r=0.70, angle=60.0, tries=3)
    d.place("bread_basket", "b", "bread basket", UPPER, r=0.70, angle=60.0, half_depth=BASKET_HALF_DEPTH)
    with pytest.raises(ValueError, match="half_depth"):
        d.place("bread_basket", "c", "bread basket", UPPER, r=0.70, angle=120.0, half_depth=0.2)


@pytest.mark.parametrize("split", ["id", "ood"])
def test_clutter_fills_both_levels(split):
    """Both levels get clutter, never more than planned (a crowded band may leave a slot empty: the
    sampler gives up after 40 tries), and some scenes get the whole plan."""
    lower_n, upper_n = TWO_LEVEL_CLUTTER
    extra = split == "ood"
    whole_plan = 0
    for seed in range(8):
        d = _draft(split, seed=seed)
        d.place("block", "task_block", "block", HIDDEN)
        n = d.add_clutter()
        model, info = d.builder.compile()
        heights = [_z(model, c.body) for c in info.clutter]
        upper = sum(z > UPPER_TOP - 0.01 for z in heights)
        lower = len(heights) - upper
        assert n == len(heights) and 1 <= upper <= upper_n + extra and 1 <= lower <= lower_n + 2 * extra
        whole_plan += upper == upper_n + extra and lower == lower_n + 2 * extra
        data = mujoco.MjData(model)
        mujoco.mj_kinematics(model, data)
        lower_r = [
            np.hypot(*data.body(c.body).xpos[:2])
            for c in info.clutter
            if _z(model, c.body) < UPPER_TOP - 0.01
        ]
        assert min(lower_r) >= TWO_LEVEL_LOWER_CLUTTER_R[0]  # beyond the sweep of the arms' two-level home
    assert whole_plan >= 1, "no scene got its whole clutter plan"


def test_the_arms_home_is_clear_of_the_upper_band():
    """HOME_ARM would put the grippers inside the slab; the two-level home holds them under it."""
    from lerobot_activearena.sim.simulator import ActiveArenaSim

    d = _draft()
    model, info = d.builder.compile()
    sim = ActiveArenaSim(model, info)
    for yaw in (0.0, -1.0, 1.0):  # the torso sweeps the arms round at home
        action = sim.home_action()
        action[TORSO_YAW] = yaw
        for _ in range(25):
            sim.step(action)
        slab = model.body("fan_level_1").id
        touching = [
            k
            for k in range(sim.data.ncon)
            if slab
            in (model.geom_bodyid[sim.data.contact[k].geom1], model.geom_bodyid[sim.data.contact[k].geom2])
        ]
        assert touching == [], yaw
    sim.close()


def test_search_views_pitch_up_to_the_upper_band():
    assert search_views(fan_workspace()) == SEARCH_VIEWS and len(SEARCH_VIEWS) == 3
    views = search_views(two_level_workspace())
    assert len(views) == 6 and [p for _, p in views] == [SEARCH_PITCH] * 3 + [UPPER_SEARCH_PITCH] * 3
    assert [y for y, _ in views[:3]] == [y for y, _ in views[3:]]


def test_the_upper_slab_and_the_column_occlude_the_lower_level():
    def visibility(workspace):
        d = SceneDraft("id", np.random.default_rng(0), workspace)
        d.builder.add_object("block", "near", 0.40, 90.0)
        d.builder.add_object("block", "far", 1.0, 60.0)  # beyond the band, on the lower fan
        d.builder.add_object("block", "beside_column", 0.90, 75.0)
        d.builder.add_object("block", "behind_column", 0.90, 90.0)
        if workspace == "two_level":
            d.builder.add_object("block", "up", 0.68, 90.0, level=1)
        model, info = d.builder.compile()
        return sector_visibility(model, info)  # rows: the search views, columns: the objects

    fan, two = visibility("fan"), visibility("two_level")
    assert fan[:, :4].any(axis=0).all()  # one level: every block is seen from some view
    assert two[:3, 0].any() and two[:3, 2].any()
    assert not two[:, 1].any()  # the upper slab hides the far lower fan
    assert not two[:, 3].any()  # the column hides what stands right behind it
    assert two[3:, 4].any()  # the upper band is searched with the head pitched up


class _TwoLevelProbe(Task):
    """A two-level layout through the real sampler: a block hidden on the lower fan and one on the
    upper band (not registered: ``name`` is set after the class is made)."""

    category = "SL"
    instruction = "Find both blocks."
    subtasks = (Subtask(1, "find", "find both blocks", 0),)
    max_episode_steps = 100
    workspace = "two_level"

    def layout(self, draft):
        draft.place("block", "low_block", "block", HIDDEN, arms=("left", "right"))
        draft.place("block", "up_block", "block", UPPER, yaw="random", arms=("left", "right"))

    def evaluate(self, sim, scene, monitor):
        return {}


_TwoLevelProbe.name = "two_level_probe"


def test_the_sampler_builds_a_task_on_its_workspace_with_the_principles_checked():
    scene = sample_scene(_TwoLevelProbe(), 0, "id")
    assert scene.info.workspace.two_level and scene.model.geom("fan_support_column") is not None
    assert [p["level"] for p in scene.params["placements"]] == [0, 1]
    vis = sector_visibility(scene.model, scene.info)
    assert not vis[0].all() and vis.any(axis=0).all()  # not all seen at home; each seen from some view
    up = scene.params["placements"][1]
    assert UPPER_REACH_R[0] <= up["r"] <= UPPER_REACH_R[1]
    assert principle_violations(_TwoLevelProbe(), scene) == []  # the upper block passed the side-reach check
    far = sample_scene(_TwoLevelProbe(), 0, "id")
    adr = far.model.jnt_qposadr[far.model.body("up_block").jntadr[0]]  # its free joint
    far.model.qpos0[adr : adr + 2] *= 0.79 / np.linalg.norm(far.model.qpos0[adr : adr + 2])  # the outer edge
    far.reach = {"up_block": ("left",)}
    assert "up_block is out of reach of the left arm" in principle_violations(_TwoLevelProbe(), far)
    again = sample_scene(_TwoLevelProbe(), 0, "id")  # deterministic
    assert again.params["placements"] == scene.params["placements"]


def test_a_task_names_a_known_workspace():
    with pytest.raises(ValueError, match="unknown workspace 'moon'"):
        type(
            "MoonTask",
            (Task,),
            {"name": "moon_probe", "category": "SS", "subtasks": (), "workspace": "moon"},
        )


@pytest.mark.parametrize("side", ["left", "right"])
def test_upper_reach_band_is_inside_what_both_arms_reach(side):
    """The upper placement band's ends, 6 cm over the upper top, are reached with the horizontal side
    grasp at the span's ends and centre; the band's outer edge is not (analysis/tasks/reach_band.py
    --level upper maps it all)."""
    for angle in (30.0, 90.0, 150.0):
        for r in UPPER_REACH_R:
            a = math.radians(angle)
            assert side_reachable([r * math.cos(a), r * math.sin(a), UPPER_TOP], side), (side, angle, r)
    assert not side_reachable([0.0, 0.80, UPPER_TOP], side)
