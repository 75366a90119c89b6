"""analysis/policies/pick_offsets.py: which arm a pick went with, how near and how far it got."""

import numpy as np
import pytest
from helpers.analysis_scripts import load


def _step(script, r, left, right, centre, grasped=(), lift=0.0):
    script.update(
        r,
        {"left": left, "right": right},
        np.asarray(centre),
        {a: a in grasped for a in ("left", "right")},
        lift,
    )


def test_the_expert_arm_is_the_one_on_the_objects_half_of_the_fan():
    script = load("analysis/policies/pick_offsets.py")
    assert script.expert_arm([-0.1, 0.4]) == "left"  # heading about 104 deg: the robot's left
    assert script.expert_arm([0.1, 0.4]) == "right"


def test_a_reach_with_the_other_arm_that_never_closes_on_the_object_is_a_reach():
    script = load("analysis/policies/pick_offsets.py")
    centre = [-0.1, 0.38, 0.05]
    r = script.new_record(centre[:2])
    _step(script, r, left=[-0.3, 0.2, 0.3], right=[-0.05, 0.35, 0.12], centre=centre)
    _step(script, r, left=[-0.3, 0.2, 0.3], right=[-0.08, 0.37, 0.09], centre=centre)
    s = script.summary(r)
    assert (s["arm"], s["expert_arm"], s["stage"]) == ("right", "left", "reach")
    assert s["nearest"] == pytest.approx(np.linalg.norm([0.02, 0.01, 0.04]))


def test_a_grasp_counts_as_a_pick_only_once_the_object_is_lifted():
    script = load("analysis/policies/pick_offsets.py")
    centre = [0.1, 0.38, 0.05]
    r = script.new_record(centre[:2])
    _step(script, r, left=[0.3, 0.2, 0.3], right=centre, centre=centre, grasped={"right"}, lift=0.01)
    assert script.summary(r)["stage"] == "grasp"
    _step(script, r, left=[0.3, 0.2, 0.3], right=centre, centre=centre, grasped={"right"}, lift=0.05)
    s = script.summary(r)
    assert (s["arm"], s["expert_arm"], s["stage"]) == ("right", "right", "lift")
    assert s["nearest"] == pytest.approx(0.0)


def test_the_object_rests_on_the_pad_it_was_set_on_and_on_no_support_on_the_table():
    import mujoco

    from lerobot_activearena.sim.simulator import ActiveArenaSim
    from lerobot_activearena.tasks import get_task
    from lerobot_activearena.tasks.sampling import sample_scene

    script = load("analysis/policies/pick_offsets.py")
    task = get_task("check_block_color")
    scene = sample_scene(task, 0, "id")
    sim = ActiveArenaSim(scene.model, scene.info)
    block = scene.obj("gray_block")
    assert script.resting_support(sim, scene, block) is None  # spawned on the table

    wrong = next(
        n for n in ("red_pad", "green_pad", "blue_pad") if n != task.read(scene, block.attributes).destination
    )
    pad = sim.data.body(wrong)
    top = pad.xpos + pad.xmat.reshape(3, 3)[:, 2] * scene.obj(wrong).functional.support.top
    joint = sim.model.body(block.body).jntadr[0]
    adr = sim.model.jnt_qposadr[joint]
    sim.data.qpos[adr : adr + 3] = top
    mujoco.mj_forward(sim.model, sim.data)
    assert script.resting_support(sim, scene, block) == wrong


def test_the_placement_names_the_miss_against_the_named_pad_and_the_nearest_other_one():
    script = load("analysis/policies/pick_offsets.py")
    r = {
        "destination": "red_pad",
        "offsets": {"red_pad": 0.052, "green_pad": 0.21, "blue_pad": 0.14},
        "held": False,
    }
    assert script.placement(r) == "  5.2 cm from it,  14.0 cm from blue_pad"
    r["held"] = True
    assert script.placement(r).endswith(", held")
    assert script.placement({"destination": "red_pad", "held": False}) == "no destination offset"


def test_a_hand_that_goes_to_the_average_place_is_told_from_one_that_follows_the_object():
    script = load("analysis/policies/pick_offsets.py")
    starts = [[0.1, 0.35], [0.15, 0.45], [-0.1, 0.4], [-0.2, 0.3]]

    def summaries(hand_at):
        out = []
        for start in starts:
            r = script.new_record(start)
            _step(script, r, left=[*hand_at(start), 0.06], right=[0.5, 0.0, 0.3], centre=[*start, 0.05])
            out.append(script.summary(r))
        return out

    follows = script.reach_tracking(summaries(lambda s: [s[0] + 0.01, s[1] - 0.01]))
    assert follows["radius_corr"] > 0.99 and follows["angle_corr"] > 0.99
    assert follows["median_miss_m"] == pytest.approx(np.hypot(0.01, 0.01))
    mean = np.mean(starts, axis=0)
    average = script.reach_tracking(summaries(lambda s: list(mean + [0.01 * s[0], 0.0])))
    assert average["median_miss_m"] > 0.5 * average["median_from_mean_m"] > 0.05
    assert abs(average["radius_corr"]) < 0.9
