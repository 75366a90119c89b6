"""blocks_ranking_size_fan_double (ML): arrange the large, medium and small blocks from left to right.

Task Description:
    As blocks_ranking_size_rotate_view on the two-level workspace: the large block stays where it
    is, on the upper band (70 %) or the lower fan; the medium block goes to its right, the small
    block to the right of the medium one, in a row on one arc. On the upper band the expert slides
    each block in with the wrist horizontal (``skills.place_on_upper``).
Randomizations:
    The row's level (upper in 70 % of episodes, as released); cube half sizes 3.0-3.3 / 2.4-2.7 /
    1.8-2.1 cm and three different colours drawn per episode (the release fixes a colour per size,
    so a policy could rank by colour); the large block at 50-150 deg, on the upper band 0.66-0.70 m
    out or in the lower arms' band, with two empty slots on its right; medium and small on the lower
    fan, one out of the home view on a random side, the other anywhere in the band; yaws random;
    clutter on both levels and (OOD) appearance.
Success Conditions:
    medium_right_of_large, small_right_of_medium: neighbours 5-15 cm apart, within 6 cm in radius
    and on the same surface (lowest points within 1 cm); all_on_a_face; all_released; all for 8
    frames, after the three were seen.
"""

from __future__ import annotations

from .blocks_ranking_size_rotate_view import RankBySize


class BlocksRankingSizeFanDouble(RankBySize):
    """The single-level row's instruction, subtasks, blocks and sizes on the two-level workspace."""

    name = "blocks_ranking_size_fan_double"
    max_episode_steps = 463
    workspace = "two_level"
    upper_share = 0.7
