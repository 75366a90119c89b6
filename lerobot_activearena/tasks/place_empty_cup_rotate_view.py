"""SL: find the cup, pick it up, find the coaster (in another part of the fan) and place the cup on it."""

from __future__ import annotations

import numpy as np

from ..expert import primitives as P
from .base import Subtask, Task, register_task
from .checks import body_touches_robot, upright
from .sampling import HIDDEN_REACH


@register_task
class PlaceEmptyCupRotateView(Task):
    name = "place_empty_cup_rotate_view"
    category = "SL"
    instruction = "Place the empty cup on the coaster."
    subtasks = (
        Subtask(1, "pick_cup", "locate and grasp the cup", 0),
        Subtask(2, "place_cup_on_coaster", "localize the coaster and place the carried cup on it", 1),
    )
    max_episode_steps = 450

    def layout(self, draft):
        # One of the two is outside the initial view (right edge); the other is on the left half.
        cup_hidden = bool(draft.rng.integers(0, 2))
        other = (100.0, 140.0)
        draft.place("cup", "cup", "cup", angle=HIDDEN_REACH if cup_hidden else other,
                    yaw=float(draft.rng.uniform(-np.pi, np.pi)))
        draft.place("coaster", "coaster", "coaster", angle=other if cup_hidden else HIDDEN_REACH)

    def reach_targets(self, scene):
        return {i: ("left", "right") for i in range(len(scene.objects))}

    def is_success(self, sim, scene):
        cup, coaster = sim.data.body("cup"), sim.data.body("coaster")
        radius = sim.info.objects[scene.objects.index("coaster")].half_extents[0]
        on_top = abs(cup.xpos[2] - (coaster.xpos[2] + 0.006)) < 0.01
        centred = np.linalg.norm(cup.xpos[:2] - coaster.xpos[:2]) < radius - 0.015
        return bool(on_top and centred and upright(sim, "cup") and not body_touches_robot(sim, "cup"))

    def expert(self, ctx, scene):
        cup, coaster = ctx.idx("cup"), ctx.idx("coaster")
        ctx.intent.subtask = 1
        yield from P.search(ctx, cup, center=False)
        side = P.arm_for(ctx.memory[cup])
        yield from P.face_for_arm(ctx, ctx.memory[cup], side)
        yield from P.pick(ctx, side, cup, closing=P.radial_tangent(ctx.center(cup)), lift=0.12)
        ctx.intent.subtask = 2
        yield from P.search(ctx, coaster, center=False)
        yield from P.face_for_arm(ctx, ctx.memory[coaster], side)
        P.start_action(ctx, {cup, coaster})
        target = ctx.center(coaster)
        yield from P.place(ctx, side, cup, target[:2], ctx.top_z(coaster) + 0.002)
        yield from P.retreat(ctx, side)
        yield from P.hold(ctx, 3)
