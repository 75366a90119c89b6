"""Where a policy's presses land on a press-device task (the bell, the stapler, the switch): per
episode, whether the device's working part went past its press threshold, and how far the instructed
arm's tool centre was from the press point (horizontally) while it did; the nearest it came at any
height (``closest``: a fly-over counts) and where it came lowest (``where lowest``: where a press
comes down; its median over the episodes whose arm reached within 20 cm). Shows what the strict
``centered_within`` check rejects that the release's check (closed gripper touching within 2.5 cm)
would count.

    python analysis/policies/press_offsets.py --policy.path=outputs/train/.../pretrained_model \\
        --env.observation_height=96 --env.observation_width=128 --episode-indices 50-69

Runs ``activearena-eval`` in this process (``--workers 1``, validation ID episodes by default) with
the pressing shape's ``evaluate`` wrapped to record each step, then prints one line per episode and
the counts.
"""

from __future__ import annotations

import argparse
import os

import numpy as np

from lerobot_activearena.tasks import predicates
from lerobot_activearena.tasks.shapes import pressing

STEPS: dict[int, dict] = {}  # scene seed -> what its episode did


def record_step(task, sim, scene) -> None:
    device = scene.obj(task.device)
    point = predicates.press_point(sim, device)
    r = STEPS.setdefault(
        scene.seed, {"pressed_offsets": [], "min_offset": 9.0, "lowest": (9.0, 9.0), "contact": False}
    )
    arm = task.arms[0]
    tcp = sim.data.site(predicates.embodiment.TCP_SITES[arm]).xpos
    offset = float(np.hypot(*(tcp[:2] - point[:2])))
    r["min_offset"] = min(r["min_offset"], offset)
    r["lowest"] = min(r["lowest"], (float(tcp[2] - point[2]), offset))  # (height, offset) where lowest
    if predicates.press_moved(sim, device):
        r["pressed_offsets"].append(offset)
        r["contact"] |= predicates.gripper_closed(sim, arm) and predicates.gripper_contact_near(
            sim, arm, task.device, point, 0.025, 0.03
        )


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--task", default="click_bell_rotate_view")
    p.add_argument("--episode-indices", default="50-69", help="manifest indices (default: validation)")
    p.add_argument("--split", default="id")
    args, eval_args = p.parse_known_args()
    from lerobot_activearena.cli.recorded import run_recorded
    from lerobot_activearena.tasks import get_task

    task = get_task(args.task)
    if not isinstance(task, pressing.PressDeviceTask):
        p.error(f"{args.task} is not a press-device task (tasks/shapes/pressing.py)")
    records = run_recorded(
        pressing.PressDeviceTask,
        record_step,
        eval_args,
        args.task,
        args.split,
        args.episode_indices,
        "press_offsets",
    )
    counts = {"success": 0, "pressed, off centre": 0, "never pressed": 0}
    for rec in records:
        nan = float("nan")
        r = STEPS.get(
            rec["scene_seed"],
            {"pressed_offsets": [], "min_offset": nan, "lowest": (nan, nan), "contact": False},
        )
        pressed = r["pressed_offsets"]
        kind = "success" if rec["success"] else ("pressed, off centre" if pressed else "never pressed")
        counts[kind] += 1
        at_press = f"{100 * min(pressed):.1f}-{100 * max(pressed):.1f} cm" if pressed else "-"
        print(
            f"episode {rec['episode']:3d}  {kind:20s} tool centre at the press {at_press:>13s}  "
            f"closest {100 * r['min_offset']:.1f} cm  where lowest {100 * r['lowest'][1]:.1f} cm  "
            f"release's contact check {'yes' if r['contact'] else 'no'}"
        )
    print(", ".join(f"{k}: {v}" for k, v in counts.items()), f"of {len(records)} episodes")
    lowest = [r["lowest"][1] for r in STEPS.values() if r["lowest"][1] < 0.2]
    if lowest:
        print(
            f"where lowest: median {100 * np.median(lowest):.1f} cm from the press point over the "
            f"{len(lowest)} episodes that reached within 20 cm; within 2 cm in {sum(x < 0.02 for x in lowest)}"
        )


if __name__ == "__main__":
    os.environ.setdefault("MUJOCO_GL", "egl")
    main()
