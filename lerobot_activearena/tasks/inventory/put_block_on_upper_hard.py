"""put_block_on_upper_hard (ML): place all blocks into the plate.

Task Description:
    Find two blocks on the lower fan and put both into the plate, which stands on the upper band
    (mostly) or on the lower fan: the policy must search both levels and remember where the plate
    and the second block are while it carries the first.
Randomizations:
    Two blocks (5 cm, random colours) on the lower fan in the arms' band: one out of the home view
    on a random side, the other anywhere; the plate (static) on the upper band at 0.70 m in 80 % of
    episodes (as released), else on the lower fan in the arms' band; clutter on both levels and
    (OOD) appearance.
Success Conditions:
    block_0_in_plate, block_1_in_plate (each resting on the plate's top on any face: centre over it,
    half its footprint), blocks_released, blocks_carried (a gripper held each up off everything
    else); all for 8 frames, after the three were seen. Failure: a block off the table.
"""

from __future__ import annotations

import numpy as np

from ...expert import arm_paths, motion, routines, skills
from .. import predicates
from ..base import Subtask, Task
from ..draft import HIDDEN, ON_UPPER_BAND, REACH, draw_level
from ..shapes.placing import carried

UPPER_SHARE = 0.8  # the release's share of episodes with the plate on the upper band
# m: the first block is set down this far beyond the plate's centre along the approach (the line
# from the robot's base), the second as far before it: the fingers close across that line, so
# neither lands on the other block, and the second never passes over the first
SPOT_OFFSET = 0.04
BLOCKS = ("block_0", "block_1")
PICK_MAX_VEL = 2.0  # rad/s: two fetches and two slides fit the paper's step limit with a margin


class PutBlockOnUpperHard(Task):
    name = "put_block_on_upper_hard"
    category = "ML"
    instruction = "Place all blocks into the plate."
    subtasks = (
        Subtask(1, "pick_a_block_0", "select and pick up the first remaining block", 0),
        Subtask(2, "place_a_block_0_into_plate", "localize the plate and place the first block inside", 1),
        Subtask(3, "pick_a_block_1", "locate and pick up the remaining block", 2),
        Subtask(4, "place_a_block_1_into_plate", "relocate the plate and place the second block inside", 3),
    )
    max_episode_steps = 323
    workspace = "two_level"

    def layout(self, draft):
        first_hidden = bool(draft.rng.integers(0, 2))
        for name, hidden in zip(BLOCKS, (first_hidden, not first_hidden), strict=True):
            draft.place(
                "block", name, "block", HIDDEN if hidden else REACH, yaw="random", arms=("left", "right")
            )
        upper = draw_level(draft, "plate", UPPER_SHARE)
        draft.place("plate", "plate", "plate", ON_UPPER_BAND if upper else REACH, static=True)

    def evaluate(self, sim, scene, monitor):
        plate = scene.obj("plate")
        checks = {
            f"{b}_in_plate": predicates.on_support(sim, scene.obj(b), plate, any_face=True) for b in BLOCKS
        }
        checks["blocks_released"] = all(predicates.released(sim, b) for b in BLOCKS)
        latched = [carried(sim, monitor, b) for b in BLOCKS]  # every latch updated each frame
        checks["blocks_carried"] = all(latched)
        return checks

    def expert(self, ctx, scene):
        plate = ctx.idx("plate")
        remaining = [ctx.idx(b) for b in BLOCKS]
        for k in range(2):
            b = routines.nearest_known(ctx, remaining)
            remaining.remove(b)
            with ctx.subtask(2 * k + 1):
                side = yield from routines.find_and_face(ctx, b)
                motion.halt(ctx, side)  # the arm that placed the first block fetches this one
                closing = arm_paths.radial_tangent(ctx.center(b))
                yield from skills.pick(
                    ctx, side, b, closing=closing, lift=0.08, approach=0.08, max_vel=PICK_MAX_VEL
                )
            with ctx.subtask(2 * k + 2):
                yield from routines.find_and_face(ctx, plate, side)
                skills.start_action(ctx, {b, plate})
                centre = ctx.center(plate)
                out = centre[:2] / np.linalg.norm(centre[:2])
                spot = centre[:2] + (SPOT_OFFSET if k == 0 else -SPOT_OFFSET) * out
                z = routines.surface_z(ctx, plate)
                if scene.params["plate_level"]:
                    yield from skills.place_on_upper(ctx, side, b, spot, z)
                else:
                    yield from skills.place(ctx, side, b, spot, z + 0.002)
                # the same arm fetches the next block straight from here; else it goes home while
                # the head and the other arm go on
                nxt = routines.nearest_known(ctx, remaining) if remaining else None
                if nxt is None or nxt not in ctx.memory or skills.arm_for(ctx.memory[nxt]) != side:
                    yield from skills.retreat(ctx, side, trailing=True)
        yield from motion.await_trailing(ctx)
        yield from motion.hold(ctx, 3)
