"""place_object_scale_rotate_view (SL): place the target object on the electronic scale.

Task Description:
    Find the one mouse or stapler on the table, pick it up, find the electronic scale elsewhere on
    the fan and set the object down on its platform.
Randomizations:
    The object's category (mouse or stapler; the release's bell has a 10 cm base, wider than the
    gripper opens) and colour; one of object / scale (random) out of the home view on a random
    side, the other anywhere in the arms' band; the scale's yaw; clutter ((OOD) never a mouse or a
    stapler: "the target object" is the only one) and (OOD) appearance.
Success Conditions:
    target_object_on_electronic_scale: the object's base rests on the platform (its centre and at
    least half its footprint over it); target_object_upright; target_object_released; all for 8
    frames, after both were seen. Failure: the object off the table.
"""

from __future__ import annotations

from ..base import Subtask
from ..shapes.placing import PickPlaceTask


class PlaceObjectScaleRotateView(PickPlaceTask):
    name = "place_object_scale_rotate_view"
    category = "SL"
    instruction = "Place the target object on the electronic scale."
    subtasks = (
        Subtask(1, "pick_object", "locate and grasp the target object", 0),
        Subtask(2, "place_object_on_scale", "localize the scale and place the object on it", 1),
    )
    max_episode_steps = 204

    obj, dest = "target_object", "electronic_scale"
    obj_choices = {"mouse": "mouse", "stapler": "stapler"}

    def dest_options(self, draft):
        return {"yaw": "random", "static": True}
