"""rank_backside_rgb_blocks (IA): read three gray blocks' hidden back colours and place them on a row
of three pads in red - green - blue order from left to right.

Task Description:
    Three gray blocks hide a red, a green and a blue patch on their back faces (facing away from
    the robot); three plain white pads lie in a row on one arc. For each block: pick it up, turn
    it until the head camera sees the patch, then place it on its pad: red on the left pad, green
    in the middle, blue on the right (left / right as the robot sees them).
Randomizations:
    Which block hides which colour; the row's radius (0.38-0.42 m) and centre heading (55-125 deg);
    one block out of the home view on a random side, the others at 40-140 deg, all at 0.34-0.42 m;
    patches face outward; clutter and (OOD) appearance.
Success Conditions:
    red_on_left_pad, green_on_middle_pad, blue_on_right_pad: each block rests on its pad (inside
    the pad less 1 cm); blocks_released: no robot contact; all for 8 frames. All three patches
    count as task information: a policy that never showed them to the camera fails as DM.
"""

from __future__ import annotations

import math

from ...expert import inspection
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Subtask
from ..draft import Region
from ..shapes.inspection import InspectAndPlaceTask, Reading

RANK = {"red": "left", "green": "middle", "blue": "right"}
BLOCKS = ("gray_block_0", "gray_block_1", "gray_block_2")
PAD_SPACING = 0.145  # m between neighbouring pad centres (2.5 cm gaps between 12 cm pads)


class RankBacksideRgbBlocks(InspectAndPlaceTask):
    name = "rank_backside_rgb_blocks"
    category = "IA"
    instruction = "Inspect three gray blocks and arrange them in red--green--blue order."
    subtasks = tuple(
        Subtask(3 * k + j + 1, name, text, j)
        for k in range(3)
        for j, (name, text) in enumerate(
            (
                ("pick_a_grey_block", "locate and pick the next gray block"),
                ("inspect_a_grey_block_backside_color", "expose and infer its hidden backside color"),
                (
                    "place_a_grey_block_on_rgb_rank_pad",
                    "localize the color-implied rank pad and place the block",
                ),
            )
        )
    )
    max_episode_steps = 697
    inspected = BLOCKS

    def layout(self, draft):
        rng = draft.rng
        r = float(rng.uniform(0.38, 0.42))
        center = float(rng.uniform(55.0, 125.0))
        step = math.degrees(2 * math.asin(PAD_SPACING / (2 * r)))
        for slot, angle in (("left", center + step), ("middle", center), ("right", center - step)):
            draft.place(
                "color_pad",
                f"{slot}_pad",
                f"{slot} pad",
                r=r,
                angle=angle,
                yaw=math.radians(angle),
                color="neutral",
                margin=0.0,
                arms=ARMS,
            )
        colors = [str(c) for c in rng.permutation(list(RANK))]
        for k, (block, color) in enumerate(zip(BLOCKS, colors, strict=True)):
            region = (
                Region(r=inspection.INSPECT_R, hidden=True)
                if k == 0
                else Region(r=inspection.INSPECT_R, angle=(40.0, 140.0))
            )
            draft.place(
                "patch_block", block, f"gray block {k + 1}", region, patch_color=color, margin=0.04, arms=ARMS
            )
        draft.params["patch_colors"] = colors
        draft.params["row"] = (round(r, 4), round(center, 2))

    def evaluate(self, sim, scene, monitor):
        checks = {}
        for block, color in zip(BLOCKS, scene.params["patch_colors"], strict=True):
            pad = scene.obj(f"{RANK[color]}_pad")
            checks[f"{color}_on_{RANK[color]}_pad"] = predicates.resting_on(sim, scene.obj(block), pad)
        checks["blocks_released"] = all(predicates.released(sim, b) for b in BLOCKS)
        return dict(
            sorted(
                checks.items(),
                key=lambda kv: list(RANK).index(kv[0].split("_")[0]) if kv[0] != "blocks_released" else 3,
            )
        )

    def read(self, scene, attributes):
        color = attributes["patch_color"]
        return Reading(color, f"{RANK[color]}_pad", f"place on the {RANK[color]} pad")
