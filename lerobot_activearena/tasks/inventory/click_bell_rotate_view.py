"""click_bell_rotate_view (SS): press the bell's top centre with the left arm.

Task Description:
    A desk bell stands out of the head camera's home view; find it, face it with the left arm and
    press its plunger with the closed gripper.
Randomizations:
    Bell at 0.35-0.48 m from the base, out of the home view on a random side (|theta - 90| >= 38.5
    deg, checked by projection), random yaw; clutter and (OOD) appearance from the sampler.
Success Conditions:
    pressed: the plunger went below its pressed threshold while the LEFT gripper, closed, touched
    the bell within 2.5 cm (xy) / 3 cm (z) of the top centre (paper's release) with its tool centre
    within 1 cm of the top centre (horizontally), the bell upright and in place at that moment; bell_upright, bell_in_place: still true afterwards.
    Failure: the bell knocked over or pushed out of place (irreversible). As for every task, the
    press counts only after the head camera has seen the bell (saw_task_objects).
"""

from __future__ import annotations

from ...expert import routines
from .. import predicates
from ..base import Subtask, Task
from ..draft import Region

CENTER_TOL = 0.01  # m: the gripper's centre over the top centre (the plunger cap's radius is 1.2 cm)


class ClickBellRotateView(Task):
    name = "click_bell_rotate_view"
    category = "SS"
    instruction = "Press the bell's top center using the left arm."
    subtasks = (Subtask(1, "_click_bell", "locate the bell and press its top center", 0),)
    max_episode_steps = 137

    def layout(self, draft):
        draft.place("bell", "bell", "bell", Region(r=(0.35, 0.48), hidden=True), yaw="random", arms=("left",))

    def evaluate(self, sim, scene, monitor):
        upright, in_place = predicates.upright(sim, "bell"), predicates.in_place(sim, "bell", 0.03)
        bell = scene.obj("bell")
        top = predicates.press_point(sim, bell)
        pressed = monitor.event(
            "pressed",
            predicates.press_moved(sim, bell)
            and predicates.pressed_by(sim, "left", "bell", top, centered_within=CENTER_TOL)
            and upright
            and in_place,
        )
        return {
            "pressed_top_center_with_left_gripper": pressed,
            "bell_upright": upright,
            "bell_in_place": in_place,
        }

    def failure(self, sim, scene, monitor):
        if predicates.knocked_over(sim, "bell"):
            return "the bell was knocked over"
        if not predicates.in_place(sim, "bell", 0.06):
            return "the bell was pushed out of place"
        return None

    def expert(self, ctx, scene):
        bell = ctx.idx("bell")
        with ctx.subtask(1):
            yield from routines.find_and_face(ctx, bell, side="left")
            yield from routines.press_object(ctx, "left", bell, depth=0.007)
            yield from routines.finish(ctx, "left")
