"""place_container_plate_rotate_view (SL): place the container on the plate.

Task Description:
    Find the container (a cup or a lidded food box), pick it up, find the plate elsewhere on the
    fan and set the container down on it.
Randomizations:
    The container's kind (cup or food box, 50/50; the release draws a bowl or a cup) and colour;
    one of container / plate (random) out of the home view on a random side, the other anywhere in
    the arms' band; clutter (never a cup or a food box) and (OOD) appearance.
Success Conditions:
    container_on_plate: the container's base rests on the plate's inner disc (its centre and at
    least half its footprint over it); container_upright; container_released; all for 8 frames,
    after both were seen. Failure: the container off the table.
"""

from __future__ import annotations

from ..base import Subtask
from ..shapes.placing import PickPlaceTask


class PlaceContainerPlateRotateView(PickPlaceTask):
    name = "place_container_plate_rotate_view"
    category = "SL"
    instruction = "Place the container on the plate."
    subtasks = (
        Subtask(1, "pick_container", "locate and grasp the container", 0),
        Subtask(2, "place_container_on_plate", "localize the plate and place the container on it", 1),
    )
    max_episode_steps = 205

    obj, dest = "container", "plate"
    obj_choices = {"cup": "cup", "container": "food box"}

    def dest_options(self, draft):
        return {"static": True}
