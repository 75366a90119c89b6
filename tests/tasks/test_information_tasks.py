"""Task-specific rules of the count, backside-inspection and can-inspection tasks (the shared
contract is in test_task_contract.py): the count the instruction asks for, every information face
seen before success, the expiry rule and its balance, and arm paths without branch jumps."""

import datetime as dt

import numpy as np
import pytest
from helpers.params import expert_task_params

from lerobot_activearena.datasets_build.plan import BuildPlan
from lerobot_activearena.envs.gym_env import ActiveArenaEnv
from lerobot_activearena.sim.action import LEFT_ARM, RIGHT_ARM
from lerobot_activearena.sim.assets.handheld import DATE_RANGE
from lerobot_activearena.sim.simulator import ActiveArenaSim
from lerobot_activearena.tasks import get_task, predicates
from lerobot_activearena.tasks.inventory.check_cola_date import expired
from lerobot_activearena.tasks.inventory.count_random_object_press_button import CATEGORIES as PLURALS
from lerobot_activearena.tasks.inventory.rank_backside_rgb_blocks import RANK
from lerobot_activearena.tasks.sampling import sample_scene
from lerobot_activearena.tasks.shapes.shaking import ShakeDetector, reversals
from lerobot_activearena.tasks.success import SuccessMonitor


def test_counterfactual_scenes_change_the_hidden_reading_and_nothing_else():
    task = get_task("check_block_color")
    scenes = [sample_scene(task, 7, "id", reading_shift=k) for k in range(3)]
    assert len({s.params["patch_color"] for s in scenes}) == 3  # each reading once
    assert [s.params.get("reading_shift", 0) for s in scenes] == [0, 1, 2]
    assert scenes[0].params == sample_scene(task, 7, "id").params  # shift 0: the benchmark's scene
    for s in scenes[1:]:
        assert s.params["placements"] == scenes[0].params["placements"]  # every object where it was
        assert s.objects == scenes[0].objects and s.hidden == scenes[0].hidden
        assert s.search_targets[1] != scenes[0].search_targets[1]  # another pad to find and place on
    with pytest.raises(ValueError, match="--reading-variants 1"):
        sample_scene(get_task("click_bell_rotate_view"), 7, "id", reading_shift=1)
    with pytest.raises(ValueError, match="--reading-variants 1"):  # a build refuses it before any episode
        BuildPlan(repo_id="a/b", split="id", tasks=["click_bell_rotate_view"], episodes=3, reading_variants=3)


def test_count_color_kinds_counts_distinct_colours_of_four_blocks():
    task = get_task("count_color_kinds_press_button")
    counts = set()
    for seed in range(8):
        scene = sample_scene(task, seed, "id")
        colors = scene.params["block_colors"]
        blocks = [n for n in scene.objects if "_block_" in n]
        assert len(colors) == 4 and len(blocks) == 4
        assert sorted(n.split("_")[0] for n in blocks) == sorted(colors)
        assert scene.params["count"] == len(set(colors))
        counts.add(scene.params["count"])
    assert counts == {1, 2, 3}


def test_count_random_object_names_the_category_and_counts_only_it():
    task = get_task("count_random_object_press_button")
    seen = set()
    for seed in range(10):
        scene = sample_scene(task, seed, "id")
        target = scene.params["target_category"]
        seen.add(target)
        counted = [o for o in scene.info.objects if o.category == target]
        assert len(counted) == scene.params["count"]
        assert f"count the {PLURALS[target]} " in scene.instruction.lower()
        others = {o.category for o in scene.info.objects if o.category not in (target, "button")}
        assert len(others) >= 1 and all(c.category != target for c in scene.info.clutter)
    assert len(seen) >= 3


def test_expiry_rule_and_balanced_cases():
    assert not expired("2024-01-01", "2024-12-31")
    assert expired("2023-01-01", "2024-01-02")  # 366 days later
    assert not expired("2023-06-01", "2024-05-31")  # 365 days later: the last valid day
    task = get_task("check_cola_date")
    states = []
    for seed in range(30):
        scene = sample_scene(task, seed, "id")
        label = scene.obj("cola_can").attributes
        today, production = scene.params["today"], label["production_date"]
        assert DATE_RANGE[0] <= dt.date.fromisoformat(production) <= dt.date.fromisoformat(today)
        assert today in scene.instruction
        assert scene.params["expired"] == expired(production, today)
        age = (dt.date.fromisoformat(today) - dt.date.fromisoformat(production)).days
        assert age != 365  # never on the boundary day
        states.append(scene.params["expired"])
    assert 8 <= sum(states) <= 22


@pytest.mark.parametrize("name", ["match_backside_two_blocks", "rank_backside_rgb_blocks"])
def test_blocks_on_their_pads_without_every_patch_seen_is_not_success(name):
    """Put every block on its pad by hand: without the camera having seen each patch, no success."""
    task = get_task(name)
    scene = sample_scene(task, 0, "id")
    sim = ActiveArenaSim(scene.model, scene.info)
    mon = SuccessMonitor(task, sim, scene)
    assert len(task.information_faces(scene)) >= 2 and not mon.info_seen
    for block, color in zip(task.information_faces(scene), scene.params["patch_colors"], strict=True):
        pad = scene.obj(f"{RANK[color]}_pad" if name.startswith("rank") else f"{color}_pad")
        j = sim.model.body(block).jntadr[0]
        adr = sim.model.jnt_qposadr[j]
        p = sim.data.body(pad.name).xpos.copy()
        offset = 0.0 if name.startswith("rank") else 0.026 * (1 if block.endswith("0") else -1)
        sim.data.qpos[adr : adr + 7] = [p[0] + offset, p[1] + offset, p[2] + 0.0045, 1, 0, 0, 0]
    all_seen = np.ones(len(scene.objects), bool)
    for _ in range(12):
        sim.step(sim.home_action())
        mon.observe(all_seen)  # every object seen, but no patch
        assert not mon.update()
    assert mon.checks["saw_task_objects"] is False
    assert all(v for k, v in mon.checks.items() if k != "saw_task_objects"), mon.checks
    mon.faces_seen = set(task.information_faces(scene))  # as if each patch had been shown
    mon.info_seen = True
    mon.observe(all_seen)
    assert any(mon.update() for _ in range(10))
    sim.close()


@pytest.mark.parametrize("name", expert_task_params("IA"))
def test_ia_expert_links_each_inspection_view_to_its_decision_without_branch_jumps(name, expert_episode):
    """The sidecar says which frame and view revealed each hidden face, what was read and what it
    decided; and a continuous arm path never switches IK branch between two frames (that whips the
    arm and flings what it holds): commanded arm joints move < 0.6 rad per frame."""
    r = expert_episode(name, 0, "id")
    assert r.success, r.failure
    task, scene = get_task(name), sample_scene(get_task(name), 0, "id")
    inspections = r.sidecar["expert_notes"]["inspections"]
    assert sorted(e["object"] for e in inspections) == sorted(task.information_faces(scene))
    for e in inspections:
        assert 0 < e["frame"] < r.length and e["reading"] and e["decision"].startswith("place")
        assert r.frames[e["frame"]]["info_complete"] == 1
    arms = np.r_[LEFT_ARM, RIGHT_ARM]
    jumps = np.abs(np.diff(r.actions[:, arms], axis=0)).max()
    assert jumps < 0.6, f"{name}: a {jumps:.2f} rad joint jump in one frame"


def _track(points, held=True, horizontal=False):
    det = ShakeDetector(horizontal)
    return any(det.update(p, held) for p in points)


def test_shake_needs_three_real_reversals_while_held():
    t = np.arange(45)
    still = [[0.4, 0.0, 0.9]] * 45
    slow = [[0.4, 0.0, 0.9 + 0.04 * np.sin(2 * np.pi * k / 90)] for k in t]  # one half wave in 3 s
    shake = [[0.4, 0.0, 0.9 + 0.04 * np.sin(2 * np.pi * k / 10)] for k in t]  # 1.5 Hz, 8 cm swings
    jitter = [[0.4, 0.0, 0.9 + 0.01 * np.sin(2 * np.pi * k / 4)] for k in t]  # fast but 2 cm swings
    assert reversals(np.array([0, 0.04, 0.0, 0.04, 0.0]), 0.03) == 3
    assert reversals(np.array([0, 0.02, 0.0, 0.02, 0.0]), 0.03) == 0
    assert not _track(still) and not _track(slow) and not _track(jitter)
    assert _track(shake) and not _track(shake, held=False)
    sideways = [[0.4, 0.04 * np.sin(2 * np.pi * k / 10), 0.9] for k in t]
    assert not _track(shake, horizontal=True), "a vertical shake is not a horizontal one"
    assert _track(sideways, horizontal=True) and _track(sideways)
    wobbly = [[0.4, 0.04 * np.sin(2 * np.pi * k / 10), 0.9 + 0.03 * (k % 10 < 5)] for k in t]
    assert not _track(wobbly, horizontal=True), "3 cm of vertical travel during a horizontal shake"


def test_a_held_bottle_that_is_not_shaken_does_not_succeed():
    """The expert's pick without its shake: lifting and holding still scores nothing."""
    env = ActiveArenaEnv(
        "shake_bottle_rotate_view", render_pixels=False, expert_channel=True, use_manifest=False
    )
    obs, info = env.reset(seed=3)
    held_frames = 0
    frozen = None
    for _ in range(env._max_episode_steps):
        if predicates.held_by_gripper(env.sim, "bottle") and predicates.lifted(env.sim, "bottle", 0.05):
            held_frames += 1
            frozen = obs["environment_state"] if frozen is None else frozen  # stop following the expert
        action = obs["environment_state"] if frozen is None else frozen
        obs, reward, terminated, truncated, info = env.step(action)
        assert not info["is_success"]
        if terminated or truncated or held_frames > 40:
            break
    assert held_frames > 40
    env.close()
