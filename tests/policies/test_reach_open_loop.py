"""analysis/policies/reach_open_loop.py: the grasp frame of a demonstration and the tool centre its
joint targets put the picking arm at."""

import numpy as np
from helpers.analysis_scripts import load


def test_the_experts_grasp_target_is_on_the_block_by_forward_kinematics():
    """On an expert demonstration of the inspection task the first gripper close is the pick, with the
    arm on the block's half of the fan, and the forward kinematics of that frame's action put the tool
    centre where the scene placed the block (distance from the base and angle round the fan)."""
    from lerobot_activearena.episodes.rollout import run_expert_episode

    script = load("analysis/policies/reach_open_loop.py")
    result = run_expert_episode("check_block_color", 3, "id")
    actions = np.asarray(result.actions)
    [(episode, g, arm)] = script.grasps(actions, np.zeros(len(actions), dtype=int))
    block = next(p for p in result.sidecar["placements"] if p["name"] == "gray_block")
    assert arm == ("left" if block["angle"] >= 90 else "right")
    r, angle = script.polar(script.ToolCentres()(actions[g], arm))
    assert abs(r - block["r"]) < 0.005 and abs(angle - block["angle"]) < 1.0
    assert actions[g - 1, 7 if arm == "left" else 15] > 0.5  # open the frame before


def test_tracking_scores_a_prediction_that_ignores_the_distance():
    """Predicted points all 38 cm from the base keep the expert's angles (correlation 1) and miss by
    the distances they ignore; a prediction on the expert's points tracks them exactly."""
    script = load("analysis/policies/reach_open_loop.py")
    angles = np.radians([40.0, 70.0, 110.0, 130.0])
    radii = np.array([0.34, 0.38, 0.36, 0.41])
    true = np.stack([radii * np.cos(angles), radii * np.sin(angles), np.full(4, 0.8)], axis=1)
    yaw = np.zeros(4)
    exact = script.tracking((true, yaw), (true, yaw), (true, yaw))
    assert exact["radius_corr"] > 0.999 and exact["median_miss_cm"] == 0.0
    flat = true.copy()
    flat[:, :2] *= (0.38 / radii)[:, None]  # every point at 38 cm, the angle kept
    off = script.tracking((flat, yaw), (true, yaw), (true, yaw))
    assert off["angle_corr"] > 0.999 and off["median_miss_cm"] > 1.0
