"""place_a2b_right_rotate_view (SL): place object A to the right of object B.

Task Description:
    Find the object the instruction names first (A), pick it up, find the second (B) and set A
    down on B's right as the robot sees it (``relations.PlaceBesideTask``).
Randomizations:
    A from seven objects a gripper can hold (Rubik's cube, mouse, stapler, wooden block, coffee box,
    toy car and, as in the paper's sentence, a bell: 8 cm wide when carried), B from the six and a
    bell or a loaf (the release's twelve less phone, cards, tea box and soap: no such assets), both
    named in the instruction; one of them (random) out of the home view on a random side, the other
    anywhere in the arms' band, at least 20 cm apart (A may start on either side of B; the release
    starts it on B's left); random yaws; clutter and (OOD) appearance.
Success Conditions:
    object_a_right_of_object_b: 8-20 cm apart, less than 8 cm apart in distance from the base, A at
    the smaller angle; object_a_upright, object_b_upright; object_a_released, object_b_released; all
    for 8 frames, after both were seen. Failure: an object off the table.
"""

from __future__ import annotations

from ..base import Subtask
from ..shapes.relations import MOVABLE, REFERENCES, PlaceBesideTask

CARRIED = {**MOVABLE, "bell": "bell"}


class PlaceA2BRightRotateView(PlaceBesideTask):
    name = "place_a2b_right_rotate_view"
    category = "SL"
    instruction = "Place the bell to the right of the coffee box."
    instruction_template = "Place the {object} to the right of the {reference}."
    instruction_values = {"object": tuple(CARRIED.values()), "reference": tuple(REFERENCES.values())}
    subtasks = (
        Subtask(1, "pick_object_A", "locate and grasp object A", 0),
        Subtask(2, "place_A_right_of_B", "localize object B and place A to its right", 1),
    )
    max_episode_steps = 198
    side = "right"
    movable = CARRIED
