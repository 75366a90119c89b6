"""place_mouse_pad_rotate_view (SL): place the mouse on the mat of the instructed colour.

Task Description:
    Find the computer mouse, pick it up, find the mat the instruction names elsewhere on the fan and
    set the mouse down on it.
Randomizations:
    One of mouse / mat (random) out of the home view on a random side, the other anywhere in the
    arms' band; mouse colour and yaw (any; the release turns it at most 45 deg); the mat's colour
    from the release's eight, named in the instruction; clutter and (OOD) appearance. The mat is
    10 x 10 cm (the release's 7 cm is narrower than the 11 cm mouse).
Success Conditions:
    mouse_on_mat: the mouse rests on the mat's top (its centre and at least half its footprint over
    it); mouse_upright; mouse_released: no robot link touches it; all for 8 frames, after both were
    seen. Failure: the mouse off the table.
"""

from __future__ import annotations

from ...sim.assets.colors import RELEASE_MAT_COLORS
from ..base import Subtask
from ..shapes.placing import PickPlaceTask, colored_mat


class PlaceMousePadRotateView(PickPlaceTask):
    name = "place_mouse_pad_rotate_view"
    category = "SL"
    instruction = "Place the mouse on the cyan mat."
    instruction_template = "Place the mouse on the {mat_color} mat."
    instruction_values = {"mat_color": RELEASE_MAT_COLORS}
    subtasks = (
        Subtask(1, "pick_mouse", "locate and grasp the mouse", 0),
        Subtask(2, "place_mouse_on_pad", "localize the mat and place the carried mouse on it", 1),
    )
    max_episode_steps = 186

    obj, dest = "mouse", "mat"

    def dest_options(self, draft):
        return colored_mat(draft)
