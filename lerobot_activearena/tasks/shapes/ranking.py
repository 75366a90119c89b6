"""Shared shape of the block-ranking tasks (ML): three blocks end in a row on one arc, left to right
as the robot sees them. The first (the anchor) stays; the expert sets the second down on its right,
then the third on the second's right.

A subclass states its row, ``blocks`` (three body names, the anchor first) and
``block_options(draft)`` (builder options per block, drawn per episode: colour, size), and may
lower the expert's ``lift`` / ``hover`` / ``approach`` (a shorter step limit). The anchor
goes at 50-150 deg in the arms' band with two empty slots on its right; one of the other two out of
the home view on a random side, the other anywhere in the band; yaws random.
Success, held 8 frames after all were seen: each block is its left neighbour's right-hand neighbour
(5-15 cm apart, within 6 cm in distance from the base, both on the table), all upright, all released.
"""

from __future__ import annotations

import math

import numpy as np

from ...expert import motion, routines, skills, view_moves
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Task
from ..draft import HIDDEN, REACH, Region

SPACING = 0.085  # m between neighbouring block centres in the final row
ANCHOR = Region(angle=(50.0, 150.0))
# Two-level variants: the anchor on the upper band (the release's row is at 0.68 m), where the
# expert sets blocks down with the horizontal side entry (``skills.place_on_upper``).
UPPER_ANCHOR = Region(r=(0.66, 0.70), angle=(50.0, 150.0), level=1)


def right_of(point, spacing: float = SPACING) -> np.ndarray:
    """The spot ``spacing`` m to the robot's right of ``point`` on the same radius."""
    r, a = predicates.polar(point)
    b = math.radians(a) - spacing / r
    return np.array([r * math.cos(b), r * math.sin(b)])


def neighbours(sim, scene, a: str, b: str) -> bool:
    """``b`` is ``a``'s right-hand neighbour in a row: on the same surface (their lowest points
    within 1 cm in height, whichever face each rests on)."""
    pa, pb = predicates.position(sim, a), predicates.position(sim, b)
    ra, rb = predicates.polar(pa)[0], predicates.polar(pb)[0]
    gap = float(np.linalg.norm(pa[:2] - pb[:2]))
    za, zb = (predicates.bottom_z(sim, scene.obj(x)) for x in (a, b))
    return (
        predicates.right_of(sim, scene.obj(b), scene.obj(a))
        and 0.05 <= gap <= 0.15
        and abs(ra - rb) <= 0.06
        and abs(za - zb) < 0.01
    )


def short(block: str) -> str:
    return block.split("_")[0]


class RankBlocksTask(Task):
    blocks: tuple[str, str, str]  # the anchor first, then left to right
    lift, hover = 0.10, 0.10  # m: how high the expert lifts a block, and comes in above its set-down
    approach = 0.12  # m above the grasp point the gripper comes in from
    upper_share = 0.0  # two-level variants: the share of episodes with the row on the upper band

    def block_options(self, draft) -> list[dict]:
        raise NotImplementedError

    def layout(self, draft):
        rng = draft.rng
        anchor, second, third = self.blocks
        options = self.block_options(draft)
        level = 0
        if self.upper_share:  # two-level: the row is on the upper band or the lower fan
            level = int(rng.random() < self.upper_share)
            draft.params["row_level"] = level
        _, r0, a0 = draft.place(
            "block",
            anchor,
            anchor.replace("_", " "),
            UPPER_ANCHOR if level else ANCHOR,
            yaw=float(rng.uniform(-0.4, 0.4)),
            arms=ARMS,
            **options[0],
        )
        step = math.degrees(SPACING / r0)
        for k in (1, 2):
            draft.reserve(r0, a0 - k * step, 0.05, level)
        hidden_first = bool(rng.integers(0, 2))
        for name, hidden, opts in ((second, hidden_first, options[1]), (third, not hidden_first, options[2])):
            draft.place(
                "block",
                name,
                name.replace("_", " "),
                HIDDEN if hidden else REACH,
                yaw="random",
                arms=ARMS,
                **opts,
            )
        draft.params["anchor_polar"] = (round(r0, 4), round(a0, 2))

    def evaluate(self, sim, scene, monitor):
        a, b, c = self.blocks
        return {
            f"{short(b)}_right_of_{short(a)}": neighbours(sim, scene, a, b),
            f"{short(c)}_right_of_{short(b)}": neighbours(sim, scene, b, c),
            # a block set down with the side entry lies on a side face
            **(
                {"all_on_a_face": all(predicates.on_a_face(sim, x, 20.0) for x in self.blocks)}
                if self.upper_share
                else {"all_upright": all(predicates.upright(sim, x, 20.0) for x in self.blocks)}
            ),
            "all_released": all(predicates.released(sim, x) for x in self.blocks),
        }

    def expert(self, ctx, scene):
        anchor, second, third = (ctx.idx(b) for b in self.blocks)
        for k, (block, ref) in enumerate(((second, anchor), (third, second))):
            with ctx.subtask(2 * k + 1):
                dest = ctx.memory.get(ref)  # where it will go, if the reference was already seen
                side = yield from routines.find_and_face(
                    ctx, block, then=None if dest is None else right_of(dest)
                )
                yield from skills.pick(ctx, side, block, lift=self.lift, approach=self.approach)
            with ctx.subtask(2 * k + 2):
                yield from view_moves.search(ctx, ref, center=False)
                target = right_of(ctx.memory[ref])
                yield from view_moves.face_for_arm(ctx, np.array([*target, ctx.memory[ref][2]]), side)
                skills.start_action(ctx, {block, ref})
                if scene.params.get("row_level"):
                    yield from skills.place_on_upper(ctx, side, block, target, ctx.bottom_z(ref))
                else:
                    yield from skills.place(ctx, side, block, target, ctx.bottom_z(ref), hover=self.hover)
                ctx.memory[block] = ctx.center(block)  # the expert knows where it put it
                yield from skills.retreat(ctx, side)
        yield from motion.hold(ctx, 3)
