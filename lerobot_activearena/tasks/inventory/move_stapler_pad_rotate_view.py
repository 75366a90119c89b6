"""move_stapler_pad_rotate_view (SL): move the stapler onto the mat of the instructed colour.

Task Description:
    Find the stapler, pick it up, find the mat the instruction names elsewhere on the fan and set the
    stapler down on it.
Randomizations:
    One of stapler / mat (random) out of the home view on a random side, the other anywhere in the
    arms' band; stapler colour and yaw; the mat's colour from the release's eight, named in the
    instruction; clutter and (OOD) appearance. The mat is 10 x 10 cm (the release's 6 cm is smaller
    than the 15 cm stapler, so "on the mat" would not be a footprint question).
Success Conditions:
    stapler_on_mat: the stapler's base rests on the mat's top (its centre and at least half its
    footprint over it); stapler_upright; stapler_released: no robot link touches it; all for 8
    frames, after both were seen. Failure: the stapler off the table.
"""

from __future__ import annotations

from ...sim.assets.colors import RELEASE_MAT_COLORS
from ..base import Subtask
from ..shapes.placing import PickPlaceTask, colored_mat


class MoveStaplerPadRotateView(PickPlaceTask):
    name = "move_stapler_pad_rotate_view"
    category = "SL"
    instruction = "Move the stapler onto the black mat."
    instruction_template = "Move the stapler onto the {mat_color} mat."
    instruction_values = {"mat_color": RELEASE_MAT_COLORS}
    subtasks = (
        Subtask(1, "pick_stapler", "locate and grasp the stapler", 0),
        Subtask(2, "place_stapler_on_pad", "localize the mat and place the carried stapler on it", 1),
    )
    max_episode_steps = 204

    obj, dest = "stapler", "mat"

    def dest_options(self, draft):
        return colored_mat(draft)
