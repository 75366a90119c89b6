"""shake_bottle_horizontally_rotate_view (SS): find the bottle, pick it up and shake it sideways.

Task Description:
    A bottle stands out of the head camera's home view. Find it, pick it up and shake it
    horizontally.
Randomizations:
    Bottle at 0.34-0.48 m, out of the home view on a random side, random yaw, colour, height
    (0.13-0.19 m) and radius (2.6-3.4 cm); clutter and (OOD) appearance.
Success Conditions:
    shaken_horizontally_while_held: while a gripper held the bottle at least 5 cm above where it
    stood with its centre within 0.8 cm of the bottle's axis, the bottle reversed direction at
    least 3 times, each swing at least 3 cm, within 3 s, along a horizontal axis, moving less than
    2 cm vertically meanwhile (a vertical shake does not count). A bottle dropped off the table
    ends the episode.
"""

from __future__ import annotations

from ..base import Subtask
from ..shapes.shaking import ShakeBottleTask


class ShakeBottleHorizontallyRotateView(ShakeBottleTask):
    name = "shake_bottle_horizontally_rotate_view"
    category = "SS"
    instruction = "Pick up the bottle and shake it horizontally."
    subtasks = (
        Subtask(
            1, "_shake_bottle_horizontally", "locate and grasp the bottle, then execute horizontal shaking", 0
        ),
    )
    max_episode_steps = 298
    horizontal = True
    bottle_r = (0.34, 0.48)  # release: 0.30-0.45; the table starts at 0.30 (a bottle there hangs off it)
