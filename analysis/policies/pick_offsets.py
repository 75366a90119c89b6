"""Where a policy's pick goes on an inspection task (check_block_color and the other
inspect-and-place tasks): per episode, the arm the expert would pick with (the one on the object's
half of the fan), the arm that came nearest the object and how near (tool centre to object centre,
3-D), whether either gripper held it with both pads, how high it was lifted, what it rests on at
the end (against the destination its reading names), how far its centre ends from the named
destination's centre and from the nearest other support's, whether a gripper still holds it, and the
episode's end. Tells a policy that
reaches with the wrong arm or to the wrong spot from one that picks and then fails the turn or the
place, a wrong destination from a missed one, and a place that misses the named pad by a little from
one that stops between pads or never lets go.

    python analysis/policies/pick_offsets.py --task check_block_color \\
        --policy.path=outputs/train/.../pretrained_model \\
        --env.observation_height=192 --env.observation_width=256 --episode-indices 50-59

Runs ``activearena-eval`` in this process (``--workers 1``, validation ID episodes by default) with
the task's ``evaluate`` wrapped to record each step, then prints one line per episode
and the counts.
"""

from __future__ import annotations

import argparse
import os
from collections import Counter

import numpy as np

from lerobot_activearena.sim.embodiment import ARMS, TCP_SITES
from lerobot_activearena.tasks import predicates
from lerobot_activearena.tasks.shapes import inspection

STEPS: dict[int, dict] = {}  # scene seed -> what its episode did
LIFT = 0.03  # m above its spawn height: picked up


def expert_arm(xy) -> str:
    """The benchmark expert's picking arm: left for an object on the robot's left half of the fan
    (heading >= 90 deg, 90 = straight ahead), right otherwise (``expert.skills.arm_for``)."""
    return "left" if np.degrees(np.arctan2(xy[1], xy[0])) >= 90.0 else "right"


def new_record(start_xy) -> dict:
    return {
        "expert_arm": expert_arm(start_xy),
        "start_xy": np.asarray(start_xy, dtype=float)[:2],
        "nearest": dict.fromkeys(ARMS, 9.0),
        "nearest_xy": dict.fromkeys(ARMS),
        "grasped": set(),
        "lift": 0.0,
        "rests_on": None,
    }


def update(r: dict, tcp: dict, centre, grasped: dict, lift: float) -> None:
    """One step: each arm's tool centre (``tcp``) against the object's centre, the arms holding it."""
    for arm in ARMS:
        distance = float(np.linalg.norm(np.asarray(tcp[arm]) - centre))
        if distance < r["nearest"][arm]:
            r["nearest"][arm], r["nearest_xy"][arm] = distance, np.asarray(tcp[arm], dtype=float)[:2]
        if grasped[arm]:
            r["grasped"].add(arm)
    r["lift"] = max(r["lift"], lift)


def summary(r: dict) -> dict:
    """What the pick did: the arm that came nearest and how near, whether that is the expert's arm,
    and the furthest it got (``reach`` < ``grasp`` < ``lift``)."""
    arm = min(ARMS, key=lambda a: r["nearest"][a])
    stage = "lift" if r["lift"] >= LIFT else ("grasp" if r["grasped"] else "reach")
    return {
        "arm": arm,
        "expert_arm": r["expert_arm"],
        "nearest": r["nearest"][arm],
        "start_xy": r["start_xy"],
        "nearest_xy": r["nearest_xy"][arm],
        "stage": stage,
        "rests_on": r["rests_on"],
    }


def polar(xy) -> tuple[float, float]:
    """(m, deg) of a table point from the robot's base: 90 deg is straight ahead."""
    return float(np.hypot(*xy)), float(np.degrees(np.arctan2(xy[1], xy[0])))


def where(xy) -> str:
    r, deg = polar(xy)
    return f"{r:.2f} m {deg:3.0f} deg"


def reach_tracking(summaries: list[dict]) -> dict[str, float]:
    """Does the hand go where the object is, or to where objects usually are? Over episodes, the
    correlation of the hand's nearest point with the object's start (polar radius and angle), and the
    hand's median miss against the object's median distance from the episodes' mean start (a hand
    that goes to the average place misses by about the latter)."""
    start = np.array([s["start_xy"] for s in summaries])
    hand = np.array([s["nearest_xy"] for s in summaries])
    sp, hp = np.array([polar(x) for x in start]), np.array([polar(x) for x in hand])
    return {
        "radius_corr": float(np.corrcoef(sp[:, 0], hp[:, 0])[0, 1]),
        "angle_corr": float(np.corrcoef(sp[:, 1], hp[:, 1])[0, 1]),
        "median_miss_m": float(np.median(np.linalg.norm(hand - start, axis=1))),
        "median_from_mean_m": float(np.median(np.linalg.norm(start - start.mean(0), axis=1))),
    }


def placement(r: dict) -> str:
    """Where the object's centre ends against the named destination and the nearest other support
    (xy, cm), and whether a gripper still holds it."""
    offsets = r.get("offsets") or {}
    if r["destination"] not in offsets:
        return "no destination offset"
    others = {k: v for k, v in offsets.items() if k != r["destination"]}
    other = min(others, key=others.get) if others else None
    text = f"{100 * offsets[r['destination']]:5.1f} cm from it"
    if other:
        text += f", {100 * others[other]:5.1f} cm from {other}"
    return text + (", held" if r["held"] else "")


def resting_support(sim, scene, obj) -> str | None:
    """The registered object with a support surface that ``obj`` rests on now, or None."""
    for name in scene.objects:
        other = scene.obj(name)
        if (
            name != obj.name
            and other.functional.support is not None
            and predicates.resting_on(sim, obj, other)
        ):
            return name
    return None


def held(sim, obj) -> bool:
    """Does either gripper hold ``obj`` with both pads now?"""
    return any(predicates.grasped_by(sim, obj.body, arm) for arm in ARMS)


def support_offsets(sim, scene, obj) -> dict[str, float]:
    """xy distance (m) from ``obj``'s centre to each registered support's centre, now."""
    centre = predicates.centre_point(sim, obj)
    return {
        name: float(np.linalg.norm(predicates.centre_point(sim, scene.obj(name))[:2] - centre[:2]))
        for name in scene.objects
        if name != obj.name and scene.obj(name).functional.support is not None
    }


def record_step(task, sim, scene) -> None:
    obj = scene.obj(task.inspected[0])
    centre = predicates.centre_point(sim, obj)
    if scene.seed not in STEPS:
        STEPS[scene.seed] = new_record(centre[:2])
    update(
        STEPS[scene.seed],
        {arm: sim.data.site(TCP_SITES[arm]).xpos.copy() for arm in ARMS},
        centre,
        {arm: predicates.grasped_by(sim, obj.body, arm) for arm in ARMS},
        float(sim.data.body(obj.body).xpos[2] - sim.model.body(obj.body).pos[2]),
    )
    record = STEPS[scene.seed]
    record["rests_on"] = resting_support(sim, scene, obj)
    record["destination"] = task.read(scene, obj.attributes).destination
    record["held"] = held(sim, obj)
    record["offsets"] = support_offsets(sim, scene, obj)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--task", default="check_block_color")
    p.add_argument("--episode-indices", default="50-59", help="manifest indices (default: validation)")
    p.add_argument("--split", default="id")
    args, eval_args = p.parse_known_args()
    from lerobot_activearena.cli.recorded import run_recorded
    from lerobot_activearena.tasks import get_task

    task = type(get_task(args.task))
    if not issubclass(task, inspection.InspectAndPlaceTask):
        p.error(f"{args.task} is not an inspect-and-place task (tasks/shapes/inspection.py)")
    records = run_recorded(
        task, record_step, eval_args, args.task, args.split, args.episode_indices, "pick_offsets"
    )
    stages, arms, ends = Counter(), Counter(), Counter()
    holds, summaries = 0, []
    for rec in records:
        s = summary(STEPS[rec["scene_seed"]])
        summaries.append(s)
        stages[s["stage"]] += 1
        arms["expert's arm" if s["arm"] == s["expert_arm"] else "the other arm"] += 1
        wanted = STEPS[rec["scene_seed"]]["destination"]
        rests = s["rests_on"] or "no support"
        ends["the named one" if rests == wanted else "another support" if s["rests_on"] else rests] += 1
        if STEPS[rec["scene_seed"]]["held"]:
            holds += 1
        end = "success" if rec["success"] else f"{rec['failure_state']}: {rec['failure_reason']}"
        print(
            f"episode {rec['episode']:3d}  expert arm {s['expert_arm']:5s}  nearest {s['arm']:5s} "
            f"{100 * s['nearest']:5.1f} cm  (object at {where(s['start_xy'])}, hand at {where(s['nearest_xy'])})  "
            f"furthest stage {s['stage']:5s}  "
            f"rests on {rests} (wanted {wanted})  {placement(STEPS[rec['scene_seed']])}  {end}"
        )
    print(f"nearest arm: {dict(arms)}; furthest stage: {dict(stages)} of {len(records)} episodes")
    print(f"object rests at the end on: {dict(ends)}; still held at the end: {holds}")
    if len(summaries) > 2:
        t = reach_tracking(summaries)
        print(
            f"the hand's nearest point against the object's start: radius corr {t['radius_corr']:.2f}, angle "
            f"corr {t['angle_corr']:.2f}; median miss {100 * t['median_miss_m']:.1f} cm (xy), the object a "
            f"median {100 * t['median_from_mean_m']:.1f} cm from the episodes' mean start"
        )


if __name__ == "__main__":
    os.environ.setdefault("MUJOCO_GL", "egl")
    main()
