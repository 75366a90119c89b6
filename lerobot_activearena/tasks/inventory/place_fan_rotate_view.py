"""place_fan_rotate_view (SL): place the fan on the mat of the instructed colour, facing the robot.

Task Description:
    Find the desk fan, pick it up by its motor housing, find the mat the instruction names
    elsewhere on the table and set the fan down on it with its front towards the robot (the
    expert carries it low: a top-down wrist turns it that far only near the table; the long way
    round where the short way meets a wrist limit).
Randomizations:
    One of fan / mat (random) out of the home view on a random side (the release always puts the
    mat on the left, by a bug), the other anywhere in the arms' band (the fan at 0.38-0.45 m);
    fan colour and yaw; the mat's colour (14 named colours), named in the instruction, 12 x 12 cm
    (the release's 10 cm is about the fan's own 9 x 10 cm box); clutter and (OOD) appearance.
Success Conditions:
    fan_on_mat: the fan's base rests on the mat's top (its centre and at least half its footprint
    over it); fan_facing_robot: its front within 30 deg of the direction to the robot's base (the
    release computes it but never checks); fan_upright; fan_released; all for 8 frames, after both
    were seen. Failure: the fan off the table.
"""

from __future__ import annotations

from dataclasses import replace

from ...sim.assets.colors import MAT_COLORS
from .. import predicates
from ..base import Subtask
from ..shapes.placing import PickPlaceTask, colored_mat

COLORS = tuple(sorted(MAT_COLORS))
FAN_R = (0.38, 0.45)  # m (the release: 0.40-0.50): nearer, the fan topples into the robot's cut-out


class PlaceFanRotateView(PickPlaceTask):
    name = "place_fan_rotate_view"
    category = "SL"
    instruction = "Place the fan on the silver mat facing the robot."
    instruction_template = "Place the fan on the {mat_color} mat facing the robot."
    instruction_values = {"mat_color": COLORS}
    subtasks = (
        Subtask(1, "pick_fan", "locate and grasp the fan", 0),
        Subtask(2, "place_fan_on_pad", "localize the mat and place the fan on it facing the robot", 1),
    )
    max_episode_steps = 179

    obj, dest = "fan", "mat"
    face_robot = True
    # Carried low: a top-down wrist can turn the fan to face the robot only near the table.
    lift, hover = 0.05, 0.05
    straight_approach = True  # the approach's joint path dipped and swept over the guard

    def regions(self, draft):
        obj_region, dest_region = super().regions(draft)
        return replace(obj_region, r=FAN_R), dest_region

    def dest_options(self, draft):
        return colored_mat(draft, COLORS, half=0.06)  # the fan's box is 9 x 10.4 cm

    def extra_checks(self, sim, scene, monitor):
        return {"fan_facing_robot": predicates.facing(sim, scene.obj("fan"), tol_deg=30.0)}
