"""put_block_on_upper_easy (SL): place the block into the upper-level plate.

Task Description:
    Find the block on the lower fan, pick it up, find the plate on the upper band (the head pitches
    up to search it) and set the block down in it: the wrist turns horizontal and slides the block
    in over the band's edge, as no top-down pose reaches the upper band.
Randomizations:
    The block (5 cm, random colour) on the lower fan in the arms' band, out of the home view on a
    random side; the plate (static) on the upper band, 0.70 m out (the band's depth leaves no
    other distance for it), anywhere in the placement span; clutter on both levels (5 lower, 3
    upper) and (OOD) appearance. Ours: the plate is always on the upper band (the instruction says
    so; the release puts it on the lower fan in 30 % of episodes under the same instruction).
Success Conditions:
    block_in_plate: the block rests on the plate's top (centre over it, at least half its footprint);
    block_released; block_carried (a gripper held it up off everything else); all for 8 frames,
    after both were seen. Failure: the block off the table.
"""

from __future__ import annotations

from ...expert import arm_paths, routines, skills
from .. import predicates
from ..base import Subtask, Task
from ..draft import HIDDEN, ON_UPPER_BAND
from ..shapes.placing import carried


class PutBlockOnUpperEasy(Task):
    name = "put_block_on_upper_easy"
    category = "SL"
    instruction = "Place the block into the upper-level plate."
    subtasks = (
        Subtask(1, "pick_a_block_0", "locate and pick up the block", 0),
        Subtask(
            2, "place_a_block_0_into_plate", "localize the upper-level plate and place the block inside", 1
        ),
    )
    max_episode_steps = 307
    workspace = "two_level"

    def layout(self, draft):
        draft.place("block", "block", "block", HIDDEN, yaw="random", arms=("left", "right"))
        draft.place("plate", "plate", "plate", ON_UPPER_BAND, static=True)

    def evaluate(self, sim, scene, monitor):
        block, plate = scene.obj("block"), scene.obj("plate")
        return {
            "block_in_plate": predicates.on_support(sim, block, plate, any_face=True),
            "block_released": predicates.released(sim, "block"),
            "block_carried": carried(sim, monitor, "block"),
        }

    def expert(self, ctx, scene):
        b, plate = ctx.idx("block"), ctx.idx("plate")
        with ctx.subtask(1):
            side = yield from routines.find_and_face(ctx, b)
            yield from skills.pick(ctx, side, b, closing=arm_paths.radial_tangent(ctx.center(b)))
        with ctx.subtask(2):
            yield from routines.find_and_face(ctx, plate, side)
            skills.start_action(ctx, {b, plate})
            yield from skills.place_on_upper(
                ctx, side, b, ctx.center(plate)[:2], routines.surface_z(ctx, plate)
            )
            yield from routines.finish(ctx, side)
