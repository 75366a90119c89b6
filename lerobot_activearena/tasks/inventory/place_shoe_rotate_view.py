"""place_shoe_rotate_view (SL): place the shoe on the mat.

Task Description:
    A 16 x 16 cm mat lies straight ahead, in the home view; find the shoe elsewhere on the fan,
    pick it up and set it down on the mat (the expert pulls the held shoe in towards the robot
    before it turns: held out at arm's length, its heel swept into clutter).
Randomizations:
    Shoe out of the home view on a random side, any yaw; the mat straight ahead (0.38-0.42 m,
    85-95 deg; the release fixes it); shoe and mat colours; clutter and (OOD) appearance.
Success Conditions:
    shoe_on_mat: the shoe's sole rests on the mat's top (its centre and at least half its
    footprint over it); shoe_upright; shoe_released: no robot link touches it (the release checks
    no release); all for 8 frames, after both were seen. Failure: the shoe off the table.
"""

from __future__ import annotations

from ..base import Subtask
from ..draft import HIDDEN, Region
from ..shapes.placing import PickPlaceTask

MAT_AHEAD = Region(r=(0.38, 0.42), angle=(85.0, 95.0), hidden=False)


class PlaceShoeRotateView(PickPlaceTask):
    name = "place_shoe_rotate_view"
    category = "SL"
    instruction = "Place the shoe on the mat."
    subtasks = (
        Subtask(1, "pick_shoe", "locate and grasp the shoe", 0),
        Subtask(2, "place_shoe_on_mat", "place the carried shoe on the mat", 1),
    )
    max_episode_steps = 170

    obj, dest = "shoe", "mat"
    carry_in = 0.30  # the 24 cm shoe would swing into clutter as the torso turns
    lift, approach, hover = 0.08, 0.08, 0.06  # nothing tall between the shoe and the mat

    def regions(self, draft):
        return HIDDEN, MAT_AHEAD

    def dest_options(self, draft):
        return {"half": (0.08, 0.08)}
