"""place_empty_cup_rotate_view (SL): place the empty cup on the coaster.

Task Description:
    Find the cup, pick it up, find the coaster (elsewhere on the fan) and set the cup down on it.
Randomizations:
    One of cup / coaster (random) out of the home view on a random side, the other anywhere in the
    arms' band (0.34-0.45 m); cup yaw random; cup and coaster colours; clutter and (OOD) appearance.
Success Conditions:
    cup_on_coaster: the cup's base rests on the coaster, centred within the coaster's radius less
    1.5 cm; cup_upright; cup_released: no robot link touches the cup; all for 8 frames.
"""

from __future__ import annotations

from .. import predicates
from ..base import Subtask
from ..shapes.placing import PickPlaceTask


class PlaceEmptyCupRotateView(PickPlaceTask):
    name = "place_empty_cup_rotate_view"
    category = "SL"
    instruction = "Place the empty cup on the coaster."
    subtasks = (
        Subtask(1, "pick_cup", "locate and grasp the cup", 0),
        Subtask(2, "place_cup_on_coaster", "localize the coaster and place the carried cup on it", 1),
    )
    max_episode_steps = 199
    obj, dest = "cup", "coaster"
    grasp_across = "radial"

    def placed(self, sim, scene):
        """The cup's base on the coaster's top, centred within the coaster's radius less 1.5 cm."""
        cup, coaster = scene.obj("cup"), scene.obj("coaster")
        return predicates.resting_on(
            sim, cup, coaster, margin=0.0, half_xy=coaster.half_extents[0] / 2**0.5
        ) and predicates.inside_disc(sim, cup, coaster, coaster.half_extents[0] - 0.015)
