"""Shared shape of the shake tasks (SS): find the bottle, pick it up and shake it while holding it.

Success is a motion, judged from the bottle's own trajectory (not the arm's commands): while a
gripper holds it at least 5 cm above where it stood, with the gripper's centre within 0.8 cm of the
bottle's axis (a grasp of the bottle, not of its edge), it must reverse direction at least 3 times,
each swing at least 3 cm, within 3 s, along one axis (``ShakeDetector``). The release only checks
the bottle's height; this is stricter: lifting and holding still, or waving it slowly, does not count.
"""

from __future__ import annotations

import colorsys
import math
from collections import deque

import numpy as np

from ...expert import arm_paths, routines, skills
from ...expert.motion import CONTROL_DT
from ...sim.embodiment import ARMS
from ...sim.workspace import TABLE_TOP
from .. import predicates
from ..base import Task
from ..draft import Region

BOTTLE = "bottle"
LIFT = 0.05  # m above its spawn height while shaking
SWING = 0.03  # m: the least swing between two reversals
REVERSALS = 3
WINDOW_S = 3.0
MAX_VERTICAL_TRAVEL = 0.02  # m, horizontal shakes only
GRASP_CENTRED = 0.008  # m: the gripper's tool centre from the bottle's axis while it shakes (expert: < 2 mm)
BOTTLE_HEIGHT = (0.13, 0.19)  # m: bottles of different sizes (the grasp height differs: a memorised
BOTTLE_RADIUS = (0.026, 0.034)  # grasp closes on air or on the shoulder of another seed's bottle)


def reversals(signal: np.ndarray, swing: float) -> int:
    """Direction reversals in a 1-D trajectory, counting only swings of at least ``swing`` (a
    hysteresis zigzag: jitter smaller than ``swing`` is no reversal)."""
    count, direction, extreme = 0, 0, float(signal[0])
    for x in signal[1:]:
        if direction >= 0 and x > extreme:
            extreme = float(x)
            direction = direction or (1 if x - signal[0] >= swing else 0)
        elif direction <= 0 and x < extreme:
            extreme = float(x)
            direction = direction or (-1 if signal[0] - x >= swing else 0)
        if direction == 1 and extreme - x >= swing:
            count, direction, extreme = count + 1, -1, float(x)
        elif direction == -1 and x - extreme >= swing:
            count, direction, extreme = count + 1, 1, float(x)
    return count


class ShakeDetector:
    """Latches once the held, lifted object has been shaken (see the module docstring).
    ``horizontal``: only horizontal axes count and the object must not travel more than 2 cm
    vertically during the shake."""

    def __init__(self, horizontal: bool):
        self.horizontal = horizontal
        self.track: deque[np.ndarray] = deque(maxlen=int(round(WINDOW_S / CONTROL_DT)))
        angles = np.radians(np.arange(0.0, 180.0, 22.5))
        self.axes = [np.array([math.cos(a), math.sin(a), 0.0]) for a in angles]
        if not horizontal:
            self.axes.append(np.array([0.0, 0.0, 1.0]))
        self.shaken = False

    def update(self, position, held_up: bool) -> bool:
        if self.shaken:
            return True
        if not held_up:  # the shake must happen in one hold
            self.track.clear()
            return False
        self.track.append(np.asarray(position, float).copy())
        if len(self.track) < 2 * REVERSALS:
            return False
        pts = np.array(self.track)
        for start in range(len(pts) - 1):
            seg = pts[start:]
            if self.horizontal and np.ptp(seg[:, 2]) > MAX_VERTICAL_TRAVEL:
                continue
            if any(reversals(seg @ ax, SWING) >= REVERSALS for ax in self.axes):
                self.shaken = True
                return True
            if not self.horizontal:
                break  # the whole window already holds every sub-window's reversals
        return False


class ShakeBottleTask(Task):
    """Base class (not registered: it defines no ``name``)."""

    horizontal: bool = False
    bottle_r: tuple[float, float] = (0.35, 0.45)

    def layout(self, draft):
        rng = draft.rng
        height, radius = float(rng.uniform(*BOTTLE_HEIGHT)), float(rng.uniform(*BOTTLE_RADIUS))
        rgba = (*colorsys.hsv_to_rgb(float(rng.uniform()), 0.7, 0.75), 1.0)
        mass = 0.15 * (height / 0.16) * (radius / 0.03) ** 2  # half-full plastic: 150 g at 16 x 6 cm
        draft.place(
            "bottle",
            BOTTLE,
            "bottle",
            Region(r=self.bottle_r, hidden=True),
            yaw="random",
            arms=ARMS,
            height=height,
            radius=radius,
            mass=mass,
            rgba=rgba,
        )
        draft.params["bottle"] = {"height": round(height, 4), "radius": round(radius, 4)}

    def evaluate(self, sim, scene, monitor):
        detector = monitor.state.setdefault("shake", ShakeDetector(self.horizontal))
        arm = predicates.held_by_gripper(sim, BOTTLE)
        held_up = (
            arm is not None
            and predicates.lifted(sim, BOTTLE, LIFT)
            and predicates.tcp_on_axis(sim, arm, BOTTLE, GRASP_CENTRED)
        )
        shaken = monitor.event("shaken", detector.update(predicates.position(sim, BOTTLE), held_up))
        name = "shaken_horizontally_while_held" if self.horizontal else "shaken_while_held"
        return {name: shaken}  # a bottle off the table ends the episode (every task's monitor)

    def expert(self, ctx, scene):
        bottle = ctx.idx(BOTTLE)
        with ctx.subtask(1):
            side = yield from routines.find_and_face(ctx, bottle)
            home = ctx.center(bottle)
            yield from skills.pick(ctx, side, bottle, closing=arm_paths.radial_tangent(home), lift=0.12)
            p, rot = arm_paths.tcp_pose(ctx, side)
            axis = np.array([0.0, 0.0, 1.0]) if not self.horizontal else arm_paths.radial_tangent(p)
            for k in range(REVERSALS + 2):  # swings of 8 cm, a little over 3 per second
                yield from arm_paths.arm_line(
                    ctx, side, p + (0.04 if k % 2 == 0 else -0.04) * axis, rot, 0.0, speed=0.45
                )
            yield from arm_paths.arm_line(ctx, side, p, rot, 0.0, speed=0.3)
            yield from skills.place(ctx, side, bottle, home[:2], TABLE_TOP, yaw_free=False)
            yield from routines.finish(ctx, side)
