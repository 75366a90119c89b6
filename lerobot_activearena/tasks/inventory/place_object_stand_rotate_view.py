"""place_object_stand_rotate_view (SL): place the named object on the display stand.

Task Description:
    Find the object the instruction names (a Rubik's cube, a mouse or a stapler), pick it up, find
    the display stand elsewhere on the fan and set the object down on the stand's top.
Randomizations:
    The object's category (Rubik's cube, mouse or stapler, named in the instruction; the release
    also draws a bell, too wide for the gripper, and a toy car and a remote control, which are
    clutter here) and yaw; one of object / stand (random) out of the home view on a random side,
    the other anywhere in the arms' band; the stand's yaw; clutter (never one of the three) and
    (OOD) appearance.
Success Conditions:
    target_object_on_display_stand: the object rests on the stand's 10 cm top (its centre over it
    and at least 40 % of its footprint: a stapler overhangs); target_object_upright;
    target_object_released; all for 8 frames, after both were seen. Failure: the object off the
    table.
"""

from __future__ import annotations

from ..base import Subtask
from ..shapes.placing import PickPlaceTask

OBJECTS = {"rubiks_cube": "Rubik's cube", "mouse": "mouse", "stapler": "stapler"}


class PlaceObjectStandRotateView(PickPlaceTask):
    name = "place_object_stand_rotate_view"
    category = "SL"
    instruction = "Place the Rubik's cube on the display stand."
    instruction_template = "Place the {object} on the display stand."
    instruction_values = {"object": tuple(OBJECTS.values())}
    subtasks = (
        Subtask(1, "pick_object", "locate and grasp the named object", 0),
        Subtask(2, "place_object_on_stand", "localize the display stand and place the object on it", 1),
    )
    max_episode_steps = 207

    obj, dest = "target_object", "display_stand"
    obj_choices = OBJECTS
    min_overlap = 0.4
    hover = 0.04  # the stand's top is 8 cm up: a higher approach leaves the arms' reach

    def dest_options(self, draft):
        return {"yaw": "random", "static": True}
