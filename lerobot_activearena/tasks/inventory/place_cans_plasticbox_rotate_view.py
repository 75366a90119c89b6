"""place_cans_plasticbox_rotate_view (ML): place both cans into the plastic box.

Task Description:
    Two cans stand on the fan, one on each side, one of them out of the home view. Find
    a can, pick it up, find the box and stand the can in it; then the other can (the expert fills
    the slot away from the robot first, then the near one).
Randomizations:
    One can out of the home view on a random side, the other anywhere in the arms' band on the other
    side (as released: one can on each side); the box on a random side (the release fixes it on the
    left; at 16 x 12 cm it cannot leave the home view inside the reach band), its long side pointing
    away from the robot give or take 15 deg, box colour; can colours; clutter and (OOD) appearance.
Success Conditions:
    first_can_in_box, second_can_in_box: each can's centre over the box's inner floor, its base
    above the floor and below the rim; both cans upright, both released; all for 8 frames, after
    every object was seen. Failure: a can off the table.
"""

from __future__ import annotations

import numpy as np

from ...expert import arm_paths, motion, routines, skills, view_moves
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Subtask, Task
from ..draft import HIDDEN, REACH, Region

CANS = ("first_can", "second_can")
BOX = Region(r=(0.38, 0.41))  # both slots (4 cm either side) stay in the reach band
SLOTS = (0.04, -0.04)  # m along the box's long (radial) axis: the far slot first, then the near one
# m: how high each can is lifted and comes in above its slot; the second clears the first can's top
LIFT, HOVER = (0.10, 0.16), (0.09, 0.09)
CAN_COLORS = ((0.75, 0.1, 0.1, 1), (0.1, 0.45, 0.8, 1), (0.95, 0.75, 0.1, 1), (0.2, 0.65, 0.3, 1))


class PlaceCansPlasticboxRotateView(Task):
    name = "place_cans_plasticbox_rotate_view"
    category = "ML"
    instruction = "Place both cans into the plastic box."
    subtasks = (
        Subtask(1, "pick_first_can", "locate and grasp the first can", 0),
        Subtask(2, "place_first_can_in_box", "localize the plastic box and place the first can in it", 1),
        Subtask(3, "pick_second_can", "locate and grasp the second can", 2),
        Subtask(4, "place_second_can_in_box", "place the second can in the plastic box", 3),
    )
    max_episode_steps = 350

    def layout(self, draft):
        hidden_side = draft.side()
        other = "left" if hidden_side == "right" else "right"
        box_side = draft.side()
        draft.place(
            "plastic_box",
            "plastic_box",
            "plastic box",
            BOX.on(box_side),
            arms=ARMS,
            yaw_jitter=0.25,
            static=True,
        )
        colors = draft.rng.choice(len(CAN_COLORS), 2, replace=False)
        regions = (HIDDEN.on(hidden_side), REACH.on(other))
        for name, region, c in zip(CANS, regions, colors, strict=True):
            draft.place("can", name, "can", region, yaw="random", arms=ARMS, rgba=CAN_COLORS[c])
        draft.clutter_excluded.add("can")

    def evaluate(self, sim, scene, monitor):
        box = scene.obj("plastic_box")
        return {
            **{f"{c}_in_box": predicates.in_container(sim, scene.obj(c), box) for c in CANS},
            **{f"{c}_upright": predicates.upright(sim, c) for c in CANS},
            **{f"{c}_released": predicates.released(sim, c) for c in CANS},
        }

    def expert(self, ctx, scene):
        box, cans = ctx.idx("plastic_box"), [ctx.idx(c) for c in CANS]
        for k, slot in enumerate(SLOTS):
            can = routines.nearest_known(ctx, cans)
            cans.remove(can)
            with ctx.subtask(2 * k + 1):
                side = yield from routines.find_and_face(ctx, can, then=ctx.memory.get(box))
                closing = arm_paths.radial_tangent(ctx.center(can))
                yield from skills.pick(ctx, side, can, closing=closing, lift=LIFT[k], approach=0.14)
            with ctx.subtask(2 * k + 2):
                yield from routines.find_and_face(ctx, box, side)
                pos, rot = ctx.pose(box)
                target = (pos + rot @ np.array([slot, 0.0, 0.0]))[:2]
                yield from view_moves.face_for_arm(ctx, np.array([*target, pos[2]]), side)
                skills.start_action(ctx, {can, box})
                yield from skills.place(
                    ctx, side, can, target, routines.surface_z(ctx, box), hover=HOVER[k], slow_last=0.04
                )
                ctx.memory[can] = ctx.center(can)
                yield from skills.retreat(ctx, side)
        yield from motion.hold(ctx, 3)
