"""shake_bottle_rotate_view (SS): find the bottle, pick it up and shake it.

Task Description:
    A bottle stands out of the head camera's home view. Find it, pick it up and shake it.
Randomizations:
    Bottle at 0.35-0.45 m, out of the home view on a random side, random yaw, colour, height
    (0.13-0.19 m) and radius (2.6-3.4 cm); clutter and (OOD) appearance.
Success Conditions:
    shaken_while_held: while a gripper held the bottle at least 5 cm above where it stood with its
    centre within 0.8 cm of the bottle's axis, the bottle reversed direction at least 3 times, each
    swing at least 3 cm, within 3 s, along one axis (measured on the bottle, not on the arm);
    a bottle dropped off the table ends the episode. Lifting and holding still, slow
    waving, or shaking a bottle caught by its edge does not count.
"""

from __future__ import annotations

from ..base import Subtask
from ..shapes.shaking import ShakeBottleTask


class ShakeBottleRotateView(ShakeBottleTask):
    name = "shake_bottle_rotate_view"
    category = "SS"
    instruction = "Pick up the bottle and shake it."
    subtasks = (
        Subtask(1, "_shake_bottle", "locate and grasp the bottle, then execute the shaking motion", 0),
    )
    max_episode_steps = 249
    bottle_r = (0.35, 0.45)
