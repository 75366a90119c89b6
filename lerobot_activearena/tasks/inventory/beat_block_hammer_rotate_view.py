"""beat_block_hammer_rotate_view (SL): grab the hammer with the instructed arm and hit the block.

Task Description:
    The hammer lies in front of the robot; the red block stands out of the home view on one side.
    Grasp the hammer by its handle with the arm the instruction names (the one on the block's side,
    as released), find the block and bring the hammer's head down on its top.
Randomizations:
    The block out of the home view on a random side (the release: either side, often in view), the
    instructed arm following it; the hammer nearly straight ahead (the release fixes it there),
    its head pointing away from the robot give or take 30 deg; hammer colour; clutter and (OOD)
    appearance.
Success Conditions:
    hit_block_with_{arm}_arm (an event): the hammer's head touches the block's top within 2 cm of
    its centre (horizontally) while both finger pads of the instructed arm hold the hammer, the
    block upright and in place; block_upright, block_in_place (within 2 cm of where it stood):
    still true 8 frames later. Failure: the block knocked over or pushed more than 6 cm.
"""

from __future__ import annotations

from ...expert import motion, routines, skills
from ...sim.assets.colors import BLOCK_COLORS
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Subtask, Task
from ..draft import Region

# The block out of the home view on the instructed arm's side; the hammer in it, nearly straight
# ahead as released but spread wider (a replayed grasp and strike from another scene misses).
HAMMER = Region(r=(0.36, 0.45), angle=(72.0, 108.0), hidden=False)
BLOCK = Region(r=(0.34, 0.48), hidden=True)
IN_PLACE, PUSHED_AWAY = 0.02, 0.06  # m


class BeatBlockHammerRotateView(Task):
    name = "beat_block_hammer_rotate_view"
    category = "SL"
    instruction = "Grab hammer using the left arm and hit the block."
    instruction_template = "Grab hammer using the {arm} arm and hit the block."
    instruction_values = {"arm": ARMS}
    subtasks = (
        Subtask(1, "pick_hammer", "locate and grasp the hammer", 0),
        Subtask(2, "hammer_block", "localize the block and hit it with the hammer", 1),
    )
    max_episode_steps = 185

    def layout(self, draft):
        side = draft.side()
        draft.params["arm"] = side
        draft.place(
            "block", "block", "red block", BLOCK.on(side), arms=(side,), rgba=BLOCK_COLORS["red"], mass=0.3
        )
        draft.place("hammer", "hammer", "hammer", HAMMER, arms=(side,), yaw_jitter=0.5)

    def evaluate(self, sim, scene, monitor):
        arm = scene.params["arm"]
        hammer, block = scene.obj("hammer"), scene.obj("block")
        upright = predicates.upright(sim, "block")
        in_place = predicates.in_place(sim, "block", IN_PLACE)
        hit = predicates.struck(sim, hammer, block) and predicates.grasped_by(sim, "hammer", arm)
        return {
            f"hit_block_with_{arm}_arm": monitor.event("hit", hit and upright and in_place),
            "block_upright": upright,
            "block_in_place": in_place,
        }

    def failure(self, sim, scene, monitor):
        if predicates.knocked_over(sim, "block"):
            return "the block was knocked over"
        if not predicates.in_place(sim, "block", PUSHED_AWAY):
            return "the block was pushed out of place"
        return None

    def expert(self, ctx, scene):
        side, hammer, block = scene.params["arm"], ctx.idx("hammer"), ctx.idx("block")
        with ctx.subtask(1):
            yield from routines.find_and_face(ctx, hammer, side)
            yield from skills.pick(ctx, side, hammer, lift=0.08, approach=0.08)
            yield from skills.hold_aside(ctx, side)
        with ctx.subtask(2):
            yield from routines.find_and_face(ctx, block, side)
            skills.start_action(ctx, {hammer, block})
            top = ctx.center(block)[:2].tolist() + [ctx.top_z(block)]
            yield from skills.strike(ctx, side, hammer, top)
            yield from motion.hold(ctx, 12)
