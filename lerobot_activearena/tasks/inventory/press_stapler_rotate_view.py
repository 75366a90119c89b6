"""press_stapler_rotate_view (SS): find the stapler and press its top arm down firmly.

Task Description:
    A desk stapler stands out of the head camera's home view. Find it and press the front end of
    its spring-loaded top arm down until the stapler closes.
Randomizations:
    Stapler at 0.40-0.48 m, out of the home view on a random side, random yaw and colour; clutter
    and (OOD) appearance.
Success Conditions:
    pressed: the top arm went down at least 0.1 rad (of its 0.14 rad travel) while a closed
    gripper touched it within 2.5 cm of the arm's front end (its press point), the stapler upright
    and in place; stapler_upright, stapler_in_place: still true afterwards. Failure: the stapler
    knocked over or pushed more than 6 cm (irreversible).
"""

from __future__ import annotations

from ...expert import routines
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Subtask, Task
from ..draft import Region


class PressStaplerRotateView(Task):
    name = "press_stapler_rotate_view"
    category = "SS"
    instruction = "Firmly press the stapler."
    subtasks = (Subtask(1, "_press_stapler", "localize and press the stapler", 0),)
    max_episode_steps = 143

    def layout(self, draft):
        draft.place(
            "stapler",
            "stapler",
            "stapler",
            Region(r=(0.40, 0.48), hidden=True),
            yaw="random",
            arms=ARMS,
        )

    def evaluate(self, sim, scene, monitor):
        stapler = scene.obj("stapler")
        upright, in_place = predicates.upright(sim, "stapler"), predicates.in_place(sim, "stapler", 0.03)
        front = predicates.press_point(sim, stapler)
        down = predicates.press_moved(sim, stapler)
        pressed = monitor.event(
            "pressed", down and predicates.pressed_by_either(sim, "stapler", front) and upright and in_place
        )
        return {"pressed_front_of_arm": pressed, "stapler_upright": upright, "stapler_in_place": in_place}

    def failure(self, sim, scene, monitor):
        if predicates.knocked_over(sim, "stapler"):
            return "the stapler was knocked over"
        if not predicates.in_place(sim, "stapler", 0.06):
            return "the stapler was pushed out of place"
        return None

    def expert(self, ctx, scene):
        stapler = ctx.idx("stapler")
        with ctx.subtask(1):
            side = yield from routines.find_and_face(ctx, stapler)
            yield from routines.press_object(ctx, side, stapler, depth=0.02)
            yield from routines.finish(ctx, side)
