"""place_object_basket_fan_double (SL): place the target object into the bread basket.

Task Description:
    Find the can on the lower fan, pick it up, find the bread basket (mostly on the upper band: the
    head pitches up to search it) and put the can in it. On the upper band the wrist turns
    horizontal, carries the can in over the basket's rim and lets it go there: it lies in the
    basket; on the lower fan the can is set down upright from above.
Randomizations:
    The can on the lower fan in the arms' band, out of the home view on a random side; the basket
    (static) on the upper band at 0.70 m, its long side along the radius, in 70 % of episodes (as
    released), else anywhere in the lower arms' band (the release fixes its lower pose: a policy
    could memorise it); clutter on both levels and (OOD) appearance.
Success Conditions:
    can_in_basket: the can's centre over the basket's inner floor, its lowest point above the floor
    and below the rim; can_released; can_carried (a gripper held it up off everything else); all
    for 8 frames, after both were seen. Failure: the can off the table.
"""

from __future__ import annotations

import math

from ...expert import arm_paths, routines, skills
from .. import predicates
from ..base import Subtask, Task
from ..draft import HIDDEN, ON_UPPER_BAND, REACH, draw_level
from ..shapes.placing import carried

UPPER_SHARE = 0.7  # the release's share of episodes with the basket on the upper band
BASKET_YAW_JITTER = 0.1  # rad about the radial direction
BASKET_HALF = (0.093, 0.068)  # m: the basket's outer half sizes (long side along its body x)
# how far it reaches along the radius, turned by up to the jitter: it must stand on the 20 cm band
BASKET_HALF_DEPTH = BASKET_HALF[0] * math.cos(BASKET_YAW_JITTER) + BASKET_HALF[1] * math.sin(
    BASKET_YAW_JITTER
)
RIM_CLEARANCE = 0.015  # m: the can comes in this far above the basket's rim


class PlaceObjectBasketFanDouble(Task):
    name = "place_object_basket_fan_double"
    category = "SL"
    instruction = "Place the target object into the bread basket."
    subtasks = (
        Subtask(1, "pick_object", "locate and pick up the target object", 0),
        Subtask(
            2, "place_object_into_basket", "localize the bread basket and place the carried object inside", 1
        ),
    )
    max_episode_steps = 299
    workspace = "two_level"

    def layout(self, draft):
        draft.place("can", "can", "can", HIDDEN, yaw="random", arms=("left", "right"))
        upper = draw_level(draft, "basket", UPPER_SHARE)
        draft.place(
            "bread_basket",
            "bread_basket",
            "bread basket",
            ON_UPPER_BAND if upper else REACH,
            static=True,
            yaw_jitter=BASKET_YAW_JITTER if upper else 0.25,
            half_depth=BASKET_HALF_DEPTH if upper else None,
        )
        draft.clutter_excluded.add("can")

    def evaluate(self, sim, scene, monitor):
        return {
            "can_in_basket": predicates.in_container(
                sim, scene.obj("can"), scene.obj("bread_basket"), any_face=True
            ),
            "can_released": predicates.released(sim, "can"),
            "can_carried": carried(sim, monitor, "can"),
        }

    def expert(self, ctx, scene):
        can, basket = ctx.idx("can"), ctx.idx("bread_basket")
        with ctx.subtask(1):
            side = yield from routines.find_and_face(ctx, can)
            yield from skills.pick(ctx, side, can, closing=arm_paths.radial_tangent(ctx.center(can)))
        with ctx.subtask(2):
            yield from routines.find_and_face(ctx, basket, side)
            skills.start_action(ctx, {can, basket})
            centre, floor = ctx.center(basket)[:2], routines.surface_z(ctx, basket)
            if scene.params["basket_level"]:
                rim = ctx.pose(basket)[0][2] + ctx.obj(basket).functional.container.rim
                over = rim + RIM_CLEARANCE - floor
                yield from skills.place_on_upper(
                    ctx, side, can, centre, floor, over=over, drop=True, from_shoulder=True
                )
            else:
                yield from skills.place(ctx, side, can, centre, floor, hover=0.12, slow_last=0.04)
            yield from routines.finish(ctx, side)
