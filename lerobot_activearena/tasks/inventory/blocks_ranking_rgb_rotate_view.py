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

import math

import numpy as np

from ...expert import primitives, routines
from ...sim.assets.task_props import BLOCK_COLORS
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Subtask, Task
from ..draft import HIDDEN, REACH, Region

SPACING = 0.085  # m between neighbouring block centres in the final row
HALF = 0.025
BLOCKS = ("red_block", "green_block", "blue_block")


def right_of(point, spacing: float = SPACING) -> np.ndarray:
    """The spot ``spacing`` m to the robot's right of ``point`` on the same radius."""
    r, a = predicates.polar(point)
    b = math.radians(a) - spacing / r
    return np.array([r * math.cos(b), r * math.sin(b)])


def neighbours(sim, a: str, b: str) -> bool:
    """``b`` is ``a``'s right-hand neighbour in a row."""
    pa, pb = predicates.position(sim, a), predicates.position(sim, b)
    ra, rb = predicates.polar(pa)[0], predicates.polar(pb)[0]
    gap = float(np.linalg.norm(pa[:2] - pb[:2]))
    return (
        predicates.right_of(sim, b, a)
        and 0.05 <= gap <= 0.15
        and abs(ra - rb) <= 0.06
        and abs(pa[2] - pb[2]) < 0.01
    )


class BlocksRankingRgbRotateView(Task):
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

    def layout(self, draft):
        rng = draft.rng
        # Red anywhere with room for two slots on its right; the slots stay empty.
        _, r_red, a_red = draft.place(
            "block",
            "red_block",
            "red block",
            Region(angle=(50.0, 150.0)),
            yaw=float(rng.uniform(-0.4, 0.4)),
            rgba=BLOCK_COLORS["red"],
            half=(HALF,) * 3,
            arms=ARMS,
        )
        step = math.degrees(SPACING / r_red)
        for k in (1, 2):
            draft.reserve(r_red, a_red - k * step, 0.05)
        hidden_first = bool(rng.integers(0, 2))
        for name, hidden in (("green_block", hidden_first), ("blue_block", not hidden_first)):
            color = name.split("_")[0]
            draft.place(
                "block",
                name,
                f"{color} block",
                HIDDEN if hidden else REACH,
                yaw="random",
                rgba=BLOCK_COLORS[color],
                half=(HALF,) * 3,
                arms=ARMS,
            )
        draft.params["red_polar"] = (round(r_red, 4), round(a_red, 2))

    def evaluate(self, sim, scene, monitor):
        return {
            "green_right_of_red": neighbours(sim, "red_block", "green_block"),
            "blue_right_of_green": neighbours(sim, "green_block", "blue_block"),
            "all_upright": all(predicates.upright(sim, b, 20.0) for b in BLOCKS),
            "all_released": all(predicates.released(sim, b) for b in BLOCKS),
        }

    def expert(self, ctx, scene):
        red, green, blue = (ctx.idx(b) for b in BLOCKS)
        for k, (block, ref) in enumerate(((green, red), (blue, green))):
            with ctx.subtask(2 * k + 1):
                dest = ctx.memory.get(ref)  # where it will go, if the reference was already seen
                side = yield from routines.find_and_face(
                    ctx, block, then=None if dest is None else right_of(dest)
                )
                yield from primitives.pick(ctx, side, block, lift=0.10)
            with ctx.subtask(2 * k + 2):
                yield from primitives.search(ctx, ref, center=False)
                target = right_of(ctx.memory[ref])
                yield from primitives.face_for_arm(ctx, np.array([*target, ctx.memory[ref][2]]), side)
                primitives.start_action(ctx, {block, ref})
                yield from primitives.place(ctx, side, block, target, ctx.bottom_z(ref))
                ctx.memory[block] = ctx.center(block)  # the expert knows where it put it
                yield from primitives.retreat(ctx, side)
        yield from primitives.hold(ctx, 3)
