"""blocks_ranking_rgb_fan_double (ML): arrange the red, green and blue blocks from left to right.

Task Description:
    As blocks_ranking_rgb_rotate_view on the two-level workspace: the red block stays where it is,
    on the upper band (70 %) or the lower fan; the green block goes to its right, the blue block to
    the right of the green one, in a row on one arc. On the upper band the expert slides each block
    in with the wrist horizontal (``skills.place_on_upper``).
Randomizations:
    The row's level (upper in 70 % of episodes, as released); the red block at 50-150 deg, on the
    upper band 0.66-0.70 m out (the release: 0.68) or in the lower arms' band, with two empty slots
    on its right; green and blue on the lower fan, one out of the home view on a random side, the
    other anywhere in the band; yaws random; clutter on both levels and (OOD) appearance.
Success Conditions:
    green_right_of_red, blue_right_of_green: neighbours 5-15 cm apart, within 6 cm in radius and
    1 cm in height (on the same level); all_on_a_face (a block slid in lies on a side face);
    all_released; all for 8 frames, after the three were seen.
"""

from __future__ import annotations

from .blocks_ranking_rgb_rotate_view import BlocksRankingRgbRotateView


class BlocksRankingRgbFanDouble(BlocksRankingRgbRotateView):
    """The single-level row's instruction, subtasks and blocks on the two-level workspace."""

    name = "blocks_ranking_rgb_fan_double"
    max_episode_steps = 480
    workspace = "two_level"
    upper_share = 0.7
