"""turn_switch_rotate_view (SS): find the rocker switch and turn it on.

Task Description:
    A rocker switch on a small base stands out of the head camera's home view. Find it and press
    the raised end of its rocker (white mark) down until the rocker is over to on.
Randomizations:
    Switch at 0.37-0.45 m, out of the home view on a random side, turned +/-45 deg from facing the
    robot; clutter and (OOD) appearance.
Success Conditions:
    switched_on: the rocker reached within 0.05 rad of its on-limit while a closed gripper touched
    it within 2.5 cm of the raised end with its tool centre within 1 cm of it (horizontally), the
    base upright and in place; switch_upright, switch_in_place: still true afterwards.
    Failure: the base knocked over or pushed more than 6 cm (irreversible).
"""

from __future__ import annotations

import math

from ...expert import routines
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Subtask, Task
from ..draft import Region

CENTER_TOL = 0.01  # m: the gripper's centre over the marked end (the rocker is 3.6 cm wide)


class TurnSwitchRotateView(Task):
    name = "turn_switch_rotate_view"
    category = "SS"
    instruction = "Locate and activate the switch."
    subtasks = (Subtask(1, "_turn_switch", "localize and trigger the switch", 0),)
    max_episode_steps = 143

    def layout(self, draft):
        draft.place(
            "switch",
            "switch",
            "switch",
            Region(r=(0.37, 0.45), hidden=True),
            yaw_jitter=math.radians(45),
            arms=ARMS,
        )

    def evaluate(self, sim, scene, monitor):
        switch = scene.obj("switch")
        upright, in_place = predicates.upright(sim, "switch"), predicates.in_place(sim, "switch", 0.03)
        end = predicates.press_point(sim, switch)
        on = predicates.press_moved(sim, switch)
        pressed = any(
            predicates.pressed_by(sim, arm, "switch", end, centered_within=CENTER_TOL) for arm in ARMS
        )
        switched = monitor.event("switched_on", on and pressed and upright and in_place)
        return {"switched_on": switched, "switch_upright": upright, "switch_in_place": in_place}

    def failure(self, sim, scene, monitor):
        if predicates.knocked_over(sim, "switch"):
            return "the switch was knocked over"
        if not predicates.in_place(sim, "switch", 0.06):
            return "the switch was pushed out of place"
        return None

    def expert(self, ctx, scene):
        switch = ctx.idx("switch")
        with ctx.subtask(1):
            side = yield from routines.find_and_face(ctx, switch)
            yield from routines.press_object(ctx, side, switch, depth=0.016)
            yield from routines.finish(ctx, side)
