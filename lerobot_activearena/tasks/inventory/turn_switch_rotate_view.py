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

from ..base import Subtask
from ..draft import Region
from ..shapes.pressing import PressDeviceTask


class TurnSwitchRotateView(PressDeviceTask):
    name = "turn_switch_rotate_view"
    category = "SS"
    instruction = "Locate and activate the switch."
    subtasks = (Subtask(1, "_turn_switch", "localize and trigger the switch", 0),)
    max_episode_steps = 143

    device = "switch"
    region = Region(r=(0.37, 0.45), hidden=True)
    placement = {"yaw_jitter": math.radians(45)}
    centered_within = 0.01  # m: over the marked end (the rocker is 3.6 cm wide)
    press_check = event = "switched_on"
    depth = 0.016
