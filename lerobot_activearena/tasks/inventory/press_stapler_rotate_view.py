"""press_stapler_rotate_view (SS): find the stapler and press its top arm down firmly.

Task Description:
    A desk stapler stands out of the head camera's home view. Find it and press the front end of
    its spring-loaded top arm down until the stapler closes.
Randomizations:
    Stapler at 0.40-0.48 m, out of the home view on a random side, random yaw and colour; clutter
    and (OOD) appearance.
Success Conditions:
    pressed: the top arm went down at least 0.1 rad (of its 0.14 rad travel) while a closed
    gripper touched it within 2.5 cm of the arm's front end (its press point) with its tool centre
    within 1.2 cm of that point (a press there, not a brush past the arm), the stapler upright and
    in place; stapler_upright, stapler_in_place: still true afterwards. Failure: the stapler
    knocked over or pushed more than 6 cm (irreversible).
"""

from __future__ import annotations

from ..base import Subtask
from ..draft import Region
from ..shapes.pressing import PressDeviceTask


class PressStaplerRotateView(PressDeviceTask):
    name = "press_stapler_rotate_view"
    category = "SS"
    instruction = "Firmly press the stapler."
    subtasks = (Subtask(1, "_press_stapler", "localize and press the stapler", 0),)
    max_episode_steps = 143

    device = "stapler"
    region = Region(r=(0.40, 0.48), hidden=True)
    press_check = "pressed_front_of_arm"
    centered_within = 0.012  # m: blind replays brushed the arm down from the side in ~8 % of scenes
    depth = 0.02
