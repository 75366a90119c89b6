"""blocks_ranking_rgb_rotate_view (ML): arrange the red, green and blue blocks from left to right.

Task Description:
    The red block stays; the green block goes to its right, the blue block to the right of the
    green one (left/right as the robot sees them), in a row on one arc.
Randomizations:
    Red block at 50-150 deg in the arms' band with two empty slots on its right; one of green / blue out
    of the home view on a random side, the other anywhere in the band; yaws random; no single view
    shows all three (principle check); clutter and (OOD) appearance.
Success Conditions:
    green_right_of_red, blue_right_of_green: neighbours 5-15 cm apart, within 6 cm in radius and
    1 cm in height; all_upright; all_released (no robot contact); all for 8 frames.
"""

from __future__ import annotations

from ...sim.assets.colors import BLOCK_COLORS
from ..base import Subtask
from ..shapes.ranking import RankBlocksTask

HALF = 0.025


class BlocksRankingRgbRotateView(RankBlocksTask):
    name = "blocks_ranking_rgb_rotate_view"
    category = "ML"
    instruction = "Arrange the red, green, and blue blocks from left to right."
    subtasks = (
        Subtask(1, "pick_green_block", "locate and grasp the green block", 0),
        Subtask(
            2, "place_green_block_right_of_red", "place the green block to the right of the red block", 1
        ),
        Subtask(3, "pick_blue_block", "locate and grasp the blue block", 2),
        Subtask(
            4, "place_blue_block_right_of_green", "place the blue block to the right of the green block", 3
        ),
    )
    max_episode_steps = 351
    blocks = ("red_block", "green_block", "blue_block")

    def block_options(self, draft):
        return [{"rgba": BLOCK_COLORS[b.split("_")[0]], "half": (HALF,) * 3} for b in self.blocks]
