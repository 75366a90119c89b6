"""match_backside_two_blocks (IA): read each gray block's hidden back colour and place it on the pad
of that colour.

Task Description:
    Two gray blocks hide coloured patches on their back faces (facing away from the robot); two
    coloured pads lie in the arms' band. For each block: pick it up, turn it until the head camera
    sees the patch, then place it on the pad of that colour. Both patches may have the same colour
    (both blocks then go on one pad).
Randomizations:
    Pad colours (two of red / green / blue); each patch colour drawn from the pads' colours
    independently; one block out of the home view on a random side, the other at 40-140 deg, both at 0.34-0.42 m;
    one pad out of the home view on the other side, the other anywhere in the band; patches face
    outward; clutter and (OOD) appearance.
Success Conditions:
    block_<k>_on_matching_pad: block k rests on the pad of its patch colour (inside the pad less
    1 cm); blocks_released: no robot contact; all for 8 frames. Both patches count as task
    information: a policy that never showed them to the camera fails as DM.
"""

from __future__ import annotations

import numpy as np

from ...expert import inspection
from ...sim.embodiment import ARMS, other_arm
from .. import predicates
from ..base import Subtask
from ..draft import HIDDEN, REACH, Region
from ..shapes.inspection import InspectAndPlaceTask, Reading

PAD_COLORS = ("red", "green", "blue")
BLOCKS = ("gray_block_0", "gray_block_1")
SHARED_PAD_OFFSET = 0.026  # m along each pad axis when both blocks go on one pad


class MatchBacksideTwoBlocks(InspectAndPlaceTask):
    name = "match_backside_two_blocks"
    category = "IA"
    instruction = "Inspect two gray blocks and place each on its matching pad."
    subtasks = tuple(
        Subtask(3 * k + j + 1, name, text, j)
        for k in range(2)
        for j, (name, text) in enumerate(
            (
                ("pick_a_grey_block", "locate and pick the next gray block"),
                (
                    "inspect_a_grey_block_backside_color",
                    "expose and infer the carried block's backside color",
                ),
                ("place_a_grey_block_on_matching_pad", "localize the matching pad and place the block"),
            )
        )
    )
    max_episode_steps = 488
    inspected = BLOCKS

    def layout(self, draft):
        rng = draft.rng
        pads = [str(c) for c in rng.choice(PAD_COLORS, size=2, replace=False)]
        patches = [pads[int(rng.integers(0, 2))] for _ in BLOCKS]
        hidden_side = draft.side()
        other = other_arm(hidden_side)
        draft.place(
            "patch_block",
            BLOCKS[0],
            "gray block 1",
            Region(r=inspection.INSPECT_R, hidden=True, side=hidden_side),
            patch_color=patches[0],
            margin=0.04,
            arms=ARMS,
        )
        draft.place(
            "color_pad",
            f"{pads[0]}_pad",
            f"{pads[0]} pad",
            HIDDEN.on(other),
            color=pads[0],
            margin=0.03,
            arms=ARMS,
        )
        draft.place(
            "color_pad", f"{pads[1]}_pad", f"{pads[1]} pad", REACH, color=pads[1], margin=0.03, arms=ARMS
        )
        draft.place(
            "patch_block",
            BLOCKS[1],
            "gray block 2",
            Region(r=inspection.INSPECT_R, angle=(40.0, 140.0)),
            patch_color=patches[1],
            margin=0.04,
            arms=ARMS,
        )
        draft.params["patch_colors"] = patches

    def search_targets(self, scene):
        pads = {f"{c}_pad" for c in scene.params["patch_colors"]}
        return [scene.objects.index(n) for n in (*BLOCKS, *sorted(pads))]

    def evaluate(self, sim, scene, monitor):
        checks = {}
        for k, (block, color) in enumerate(zip(BLOCKS, scene.params["patch_colors"], strict=True)):
            pad = scene.obj(f"{color}_pad")
            checks[f"block_{k}_on_matching_pad"] = predicates.resting_on(sim, scene.obj(block), pad)
        checks["blocks_released"] = all(predicates.released(sim, b) for b in BLOCKS)
        return checks

    def read(self, scene, attributes):
        color = attributes["patch_color"]
        return Reading(color, f"{color}_pad", f"place on the {color} pad")

    def place_spot(self, ctx, scene, dest, reading, placed_before):
        shared = scene.params["patch_colors"].count(reading.value) == 2
        return pad_spot(ctx, dest, placed_before, shared)


def pad_spot(ctx, pad: int, n_on_it: int, shared: bool) -> np.ndarray:
    """Where on the pad the next block goes: the centre, or (two blocks on one pad) one of two
    spots on the pad's diagonal, far enough apart for blocks of any yaw."""
    c, rot = ctx.pose(pad)
    if not shared:
        return ctx.center(pad)[:2]
    sign = 1.0 if n_on_it == 0 else -1.0
    return (c + rot @ np.array([sign * SHARED_PAD_OFFSET, sign * SHARED_PAD_OFFSET, 0.0]))[:2]
