"""blocks_ranking_size_rotate_view (ML): arrange the large, medium and small blocks from left to right.

Task Description:
    The large block stays; the medium block goes to its right, the small block to the right of the
    medium one (left/right as the robot sees them), in a row on one arc (``ranking.RankBlocksTask``).
Randomizations:
    Cube half sizes 3.0-3.3 / 2.4-2.7 / 1.8-2.1 cm (the release's); three different colours drawn
    per episode (a colour says nothing about the size); large block at 50-150 deg with two empty
    slots on its right; one of medium / small out of the home view on a random side, the other
    anywhere in the band; yaws random; clutter and (OOD) appearance.
Success Conditions:
    medium_right_of_large, small_right_of_medium: neighbours 5-15 cm apart, within 6 cm in distance
    from the base, both on the table; all_upright; all_released; all for 8 frames.
"""

from __future__ import annotations

from ...sim.assets.colors import BLOCK_COLORS
from ..base import Subtask
from ..shapes.ranking import RankBlocksTask

HALF_SIZES = {"large_block": (0.030, 0.033), "medium_block": (0.024, 0.027), "small_block": (0.018, 0.021)}


class RankBySize(RankBlocksTask):
    """The size row (instruction, subtasks, blocks and their sizes) on either workspace."""

    category = "ML"
    instruction = "Arrange the large, medium, and small blocks from left to right."
    subtasks = (
        Subtask(1, "pick_medium_block", "locate and grasp the medium block", 0),
        Subtask(
            2,
            "place_medium_block_right_of_large",
            "place the medium block to the right of the large block",
            1,
        ),
        Subtask(3, "pick_small_block", "locate and grasp the small block", 2),
        Subtask(
            4,
            "place_small_block_right_of_medium",
            "place the small block to the right of the medium block",
            3,
        ),
    )
    blocks = ("large_block", "medium_block", "small_block")

    def block_options(self, draft):
        colors = draft.rng.choice(sorted(BLOCK_COLORS), size=3, replace=False)
        return [
            {"rgba": BLOCK_COLORS[str(c)], "half": (float(draft.rng.uniform(*HALF_SIZES[b])),) * 3}
            for b, c in zip(self.blocks, colors, strict=True)
        ]


class BlocksRankingSizeRotateView(RankBySize):
    name = "blocks_ranking_size_rotate_view"
    max_episode_steps = 303
    # Lower than rgb's (its step limit is 48 shorter); a 6 cm lift sweeps the large block.
    lift, hover, approach = 0.08, 0.05, 0.07
