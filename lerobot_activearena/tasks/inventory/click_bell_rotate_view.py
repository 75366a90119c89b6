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
    within 1 cm of the top centre (horizontally), the bell upright and in place at that moment;
    bell_upright, bell_in_place: still true afterwards. Failure: the bell knocked over or pushed out
    of place (irreversible). As for every task, the press counts only after the head camera has
    seen the bell (saw_task_objects).
"""

from __future__ import annotations

from ..base import Subtask
from ..draft import Region
from ..shapes.pressing import PressDeviceTask


class ClickBellRotateView(PressDeviceTask):
    name = "click_bell_rotate_view"
    category = "SS"
    instruction = "Press the bell's top center using the left arm."
    subtasks = (Subtask(1, "_click_bell", "locate the bell and press its top center", 0),)
    max_episode_steps = 137

    device = "bell"
    region = Region(r=(0.35, 0.48), hidden=True)
    arms = ("left",)
    centered_within = 0.01  # m: over the top centre (the plunger cap's radius is 1.2 cm)
    press_check = "pressed_top_center_with_left_gripper"
    depth = 0.007
