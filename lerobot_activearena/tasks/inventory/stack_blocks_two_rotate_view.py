"""stack_blocks_two_rotate_view (SL): stack the green block on the red block.

Task Description:
    Find the green block, pick it up, find the red block and set the green one down on its top.
Randomizations:
    Green or red block (random) out of the home view on a random side, the other anywhere in the
    arms' band (the release lets both share the home view); 5 cm cubes as released; random yaw for
    the green block; no other block in the clutter; clutter and (OOD) appearance.
Success Conditions:
    green_block_on_red_block: centres within 2.5 cm horizontally and the green block's base at the
    red block's top (+/- 1.2 cm); both upright; both released (the robot off them); all for 8
    frames, after both were seen. Failure: a block off the table.
"""

from __future__ import annotations

from ...sim.assets.colors import BLOCK_COLORS
from .. import predicates
from ..base import Subtask
from ..shapes.placing import PickPlaceTask

HALF = (0.025,) * 3  # m: the release's cubes


class StackBlocksTwoRotateView(PickPlaceTask):
    name = "stack_blocks_two_rotate_view"
    category = "SL"
    instruction = "Stack the green block on the red block."
    subtasks = (
        Subtask(1, "pick_green_block", "locate and grasp the green block", 0),
        Subtask(2, "stack_green_on_red", "localize the red block and stack the green block on it", 1),
    )
    max_episode_steps = 223

    obj, dest = "green_block", "red_block"
    obj_asset = dest_asset = "block"
    lift, hover = 0.08, 0.05  # carried low: on top of the red block, high set-downs leave the reach

    def obj_options(self, draft):
        return {"rgba": BLOCK_COLORS["green"], "half": HALF}

    def dest_options(self, draft):
        return {"rgba": BLOCK_COLORS["red"], "half": HALF}

    def evaluate(self, sim, scene, monitor):
        green, red = scene.obj(self.obj), scene.obj(self.dest)
        return {
            "green_block_on_red_block": predicates.stacked_on(sim, green, red),
            **{f"{b}_upright": predicates.upright(sim, b) for b in (self.obj, self.dest)},
            **{f"{b}_released": predicates.released(sim, b) for b in (self.obj, self.dest)},
        }
