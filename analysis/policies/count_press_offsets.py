"""Where a policy's arm goes on a count-and-press task: per episode, where the instructed arm's tool
centre came lowest, how far that was (horizontally) from each of the three buttons' press points and
from their centroid, and which button it was nearest. A policy unsure which button to press, trained
with a regression loss, tends to aim between them: its lowest point then lies nearer the buttons'
centroid than any button.

    python analysis/policies/count_press_offsets.py --policy.path=outputs/train/.../pretrained_model \\
        --policy.device=cpu --env.observation_height=192 --env.observation_width=256 --episode-indices 50-69

Runs ``activearena-eval`` in this process (``--workers 1``, validation ID episodes by default) with
the counting shape's ``evaluate`` wrapped to record each step, then prints one line per episode and
the counts.
"""

from __future__ import annotations

import argparse
import os

import numpy as np

from lerobot_activearena.tasks import predicates
from lerobot_activearena.tasks.shapes import counting

STEPS: dict[int, dict] = {}  # scene seed -> where its episode's arm came lowest
ARM = {"value": "left"}


def record_step(task, sim, scene) -> None:
    points = {n: predicates.press_point(sim, scene.obj(f"button_{n}")) for n in counting.BUTTONS}
    tcp = sim.data.site(predicates.embodiment.TCP_SITES[ARM["value"]]).xpos.copy()
    r = STEPS.setdefault(scene.seed, {"lowest": None, "count": scene.params["count"], "points": points})
    if r["lowest"] is None or tcp[2] < r["lowest"][2]:
        r["lowest"] = tcp
        r["torso"] = float(np.degrees(sim.data.joint(predicates.embodiment.TORSO_YAW_JOINT).qpos[0]))


def offsets(r: dict) -> dict:
    """Horizontal distances (m) of the lowest point from each button and from their centroid, and
    its bearing (deg, about the robot's base: the torso's turn) and reach (m) from the matching one."""
    low = r["lowest"][:2]
    dist = {n: float(np.hypot(*(low - p[:2]))) for n, p in r["points"].items()}
    centroid = np.mean([p[:2] for p in r["points"].values()], axis=0)
    nearest = min(dist, key=dist.get)
    target = r["points"][r["count"]][:2]
    azimuth = np.degrees(np.arctan2(low[1], low[0]) - np.arctan2(target[1], target[0]))
    return {
        "azimuth": float((azimuth + 180) % 360 - 180),
        "radial": float(np.hypot(*low) - np.hypot(*target)),
        "target_bearing": float(np.degrees(np.arctan2(target[1], target[0])) - 90.0),
        "nearest": nearest,
        "to_nearest": dist[nearest],
        "to_matching": dist[r["count"]],
        "to_centroid": float(np.hypot(*(low - centroid))),
        "height": float(r["lowest"][2] - r["points"][nearest][2]),
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--task", default="count_target_press_button")
    p.add_argument("--arm", default="left", choices=("left", "right"), help="the arm the policy presses with")
    p.add_argument("--episode-indices", default="50-69", help="manifest indices (default: validation)")
    p.add_argument("--split", default="id")
    args, eval_args = p.parse_known_args()
    from lerobot_activearena.cli.recorded import run_recorded
    from lerobot_activearena.tasks import get_task

    if not isinstance(get_task(args.task), counting.CountAndPressTask):
        p.error(f"{args.task} is not a count-and-press task (tasks/shapes/counting.py)")
    ARM["value"] = args.arm
    records = run_recorded(
        counting.CountAndPressTask,
        record_step,
        eval_args,
        args.task,
        args.split,
        args.episode_indices,
        "count_press_offsets",
    )
    all_o = [offsets(STEPS[r["scene_seed"]]) for r in records]
    between = sum(o["to_centroid"] < o["to_nearest"] for o in all_o)
    for rec, o in zip(records, all_o, strict=True):
        print(
            f"episode {rec['episode']:3d}  {'success' if rec['success'] else rec['failure_state'] or '-':8s} "
            f"count {STEPS[rec['scene_seed']]['count']}  lowest {100 * o['height']:5.1f} cm above, "
            f"nearest button {o['nearest']} at {100 * o['to_nearest']:.1f} cm, matching at "
            f"{100 * o['to_matching']:.1f} cm, centroid at {100 * o['to_centroid']:.1f} cm; from the matching one "
            f"{o['azimuth']:+.1f} deg about the base (it lies {o['target_bearing']:+.0f} deg from straight ahead; "
            f"the torso then at {STEPS[rec['scene_seed']].get('torso', float('nan')):+.0f} deg), {100 * o['radial']:+.1f} cm radially"
        )
    target = np.array([o["target_bearing"] for o in all_o])
    reached = target + np.array([o["azimuth"] for o in all_o])
    slope = np.polyfit(target, reached, 1)[0] if len(records) > 1 else float("nan")
    torso = np.array([STEPS[r["scene_seed"]].get("torso", np.nan) for r in records])
    torso_slope = np.polyfit(target, torso, 1)[0] if len(records) > 1 else float("nan")
    print(
        f"{len(records)} episodes: lowest point nearer the buttons' centroid than any button in {between}; "
        f"median {100 * np.median([o['to_nearest'] for o in all_o]):.1f} cm from the nearest button, "
        f"{100 * np.median([o['height'] for o in all_o]):.1f} cm above it; nearest is the matching one in "
        f"{sum(o['nearest'] == STEPS[r['scene_seed']]['count'] for o, r in zip(all_o, records, strict=True))}; "
        f"its bearing against the matching button's: slope {slope:.2f} (1: the turn follows the button, "
        f"0: it comes down straight ahead whatever the button); "
        f"the torso's yaw there against it: slope {torso_slope:.2f}"
    )


if __name__ == "__main__":
    os.environ.setdefault("MUJOCO_GL", "egl")
    main()
