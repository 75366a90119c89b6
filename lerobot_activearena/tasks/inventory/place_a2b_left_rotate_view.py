"""place_a2b_left_rotate_view (SL): place object A to the left of object B.

Task Description:
    Find the object the instruction names first (A), pick it up, find the second (B) and set A
    down on B's left as the robot sees it (``relations.PlaceBesideTask``).
Randomizations:
    A from six objects a gripper can hold (Rubik's cube, mouse, stapler, wooden block, coffee box,
    toy car), B from those and a bell or a loaf (the release's twelve less phone, cards, tea box and
    soap: no such assets), both named in the instruction; one of them (random) out of the home view
    on a random side, the other anywhere in the arms' band, at least 20 cm apart (A may start on
    either side of B; the release starts it on B's right); random yaws; clutter and (OOD) appearance.
Success Conditions:
    object_a_left_of_object_b: 8-20 cm apart, less than 8 cm apart in distance from the base, A at
    the larger angle; object_a_upright, object_b_upright; object_a_released, object_b_released; all
    for 8 frames, after both were seen. Failure: an object off the table.
"""

from __future__ import annotations

from ..base import Subtask
from ..shapes.relations import PlaceBesideTask


class PlaceA2BLeftRotateView(PlaceBesideTask):
    name = "place_a2b_left_rotate_view"
    category = "SL"
    instruction = "Place the Rubik's cube to the left of the wooden block."
    instruction_template = "Place the {object} to the left of the {reference}."
    subtasks = (
        Subtask(1, "pick_object_A", "locate and grasp object A", 0),
        Subtask(2, "place_A_left_of_B", "localize object B and place A to its left", 1),
    )
    max_episode_steps = 192
    side = "left"
