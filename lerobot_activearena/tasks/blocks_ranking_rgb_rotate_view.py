"""ML: arrange the red, green and blue blocks from left to right (as the robot sees them): the red
block stays, green goes to its right, blue to the right of green. The blocks are spread so that no
single view shows all three."""

from __future__ import annotations

import math

import numpy as np

from ..expert import primitives as P
from ..sim.assets.task_props import BLOCK_COLORS
from .base import Subtask, Task, register_task
from .checks import body_touches_robot, polar, upright
from .sampling import HIDDEN_REACH

SPACING = 0.085  # m between neighbouring block centres in the final row
HALF = 0.025


def right_of(point, spacing: float = SPACING) -> np.ndarray:
    """The spot ``spacing`` m to the robot's right of ``point`` on the same radius."""
    r, a = polar(point)
    b = math.radians(a) - spacing / r
    return np.array([r * math.cos(b), r * math.sin(b)])


@register_task
class BlocksRankingRgbRotateView(Task):
    name = "blocks_ranking_rgb_rotate_view"
    category = "ML"
    instruction = "Arrange the red, green, and blue blocks from left to right."
    subtasks = (
        Subtask(1, "pick_green_block", "locate and grasp the green block", 0),
        Subtask(2, "place_green_block_right_of_red", "place the green block to the right of the red block", 1),
        Subtask(3, "pick_blue_block", "locate and grasp the blue block", 2),
        Subtask(4, "place_blue_block_right_of_green", "place the blue block to the right of the green block", 3),
    )
    max_episode_steps = 800

    def layout(self, draft):
        rng = draft.rng
        # Red anywhere from 60 to 150 deg with room for two slots on its right; the slots stay empty.
        _, r_red, a_red = draft.place("block", "red_block", "red block", angle=(62.0, 145.0), yaw=float(rng.uniform(-0.4, 0.4)) + 0.0,
                                      rgba=BLOCK_COLORS["red"], half=(HALF,) * 3)
        step = math.degrees(SPACING / r_red)
        for k in (1, 2):
            draft.reserve(r_red, a_red - k * step, 0.05)
        # One of green/blue is outside the initial view (right edge); the other elsewhere.
        hidden_first = bool(rng.integers(0, 2))
        for name, hidden in (("green_block", hidden_first), ("blue_block", not hidden_first)):
            color = name.split("_")[0]
            draft.place("block", name, f"{color} block", angle=HIDDEN_REACH if hidden else (40.0, 150.0),
                        yaw=float(rng.uniform(-np.pi, np.pi)), rgba=BLOCK_COLORS[color], half=(HALF,) * 3)
        draft.params["red_polar"] = (round(r_red, 4), round(a_red, 2))

    def reach_targets(self, scene):
        return {i: ("left", "right") for i in range(len(scene.objects))}

    def is_success(self, sim, scene):
        pts = {}
        for c in ("red", "green", "blue"):
            body = f"{c}_block"
            if body_touches_robot(sim, body) or not upright(sim, body, 20.0):
                return False
            pts[c] = sim.data.body(body).xpos.copy()
        for a, b in (("red", "green"), ("green", "blue")):
            ra, aa = polar(pts[a])
            rb, ab = polar(pts[b])
            gap = float(np.linalg.norm(pts[a][:2] - pts[b][:2]))
            if not (aa > ab and 0.05 <= gap <= 0.15 and abs(ra - rb) <= 0.06 and abs(pts[a][2] - pts[b][2]) < 0.01):
                return False
        return True

    def expert(self, ctx, scene):
        red, green, blue = ctx.idx("red_block"), ctx.idx("green_block"), ctx.idx("blue_block")
        anchor = red
        for sid, (block, ref) in enumerate(((green, red), (blue, green))):
            ctx.intent.subtask = 2 * sid + 1
            yield from P.search(ctx, block, center=False)
            dest = ctx.memory.get(ref)  # where it will go, if the reference was already seen
            side = P.arm_for(ctx.memory[block], None if dest is None else right_of(dest))
            yield from P.face_for_arm(ctx, ctx.memory[block], side)
            yield from P.pick(ctx, side, block, lift=0.10)
            ctx.intent.subtask = 2 * sid + 2
            yield from P.search(ctx, ref, center=False)
            target = right_of(ctx.memory[ref])
            yield from P.face_for_arm(ctx, np.array([*target, ctx.memory[ref][2]]), side)
            P.start_action(ctx, {block, ref})
            surface = ctx.bottom_z(ref)
            yield from P.place(ctx, side, block, target, surface)
            ctx.memory[block] = ctx.center(block)  # the expert knows where it put it
            yield from P.retreat(ctx, side)
        del anchor
        yield from P.hold(ctx, 3)
