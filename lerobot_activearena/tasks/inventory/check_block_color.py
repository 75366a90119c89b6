"""check_block_color (IA): read the gray block's hidden back colour and place it on that pad.

Task Description:
    A gray block hides a coloured patch on its back face (facing away from the robot). Pick it up,
    turn it in the hand until the head camera sees the patch, turn it back, then find the pad of
    that colour and place the block on it.
Randomizations:
    Patch colour (red / green / blue); pad colours permuted: one pad out of the home view on a
    random side, two anywhere in the arms' band; block at 40-140 deg and 0.34-0.42 m, patch facing outward;
    clutter and (OOD) appearance.
Success Conditions:
    on_matching_pad: the block rests on the pad of its patch colour (inside the pad less 1 cm);
    block_released: no robot contact; both for 8 frames. The patch counts as task-relevant
    information: a policy that never showed it to the camera fails as DM.
"""

from __future__ import annotations

from ...expert import inspection
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Subtask
from ..draft import HIDDEN, Region
from ..shapes.inspection import InspectAndPlaceTask, Reading

PAD_COLORS = ("red", "green", "blue")


class CheckBlockColor(InspectAndPlaceTask):
    name = "check_block_color"
    category = "IA"
    instruction = "Inspect the gray block's hidden color and place it on the matching pad."
    subtasks = (
        Subtask(1, "pick_target_block", "locate and pick up the gray target block", 0),
        Subtask(2, "inspect_target_block_backside", "reveal and identify the block's backside color", 1),
        Subtask(3, "restore_target_block_pose", "restore the block to a placement-ready pose", 2),
        Subtask(
            4, "place_target_block_on_matching_pad", "localize the matching pad and place the block on it", 3
        ),
    )
    max_episode_steps = 296
    inspected = ("gray_block",)
    restore_before_placing = True
    fine_print = True  # the patch is a few pixels at 192 x 256: turned where the camera sees it frontally

    def layout(self, draft):
        rng = draft.rng
        colors = list(rng.permutation(PAD_COLORS))
        arms = ARMS
        draft.place(
            "color_pad",
            f"{colors[0]}_pad",
            f"{colors[0]} pad",
            HIDDEN,
            color=colors[0],
            margin=0.03,
            arms=arms,
        )
        for c in colors[1:]:
            draft.place(
                "color_pad",
                f"{c}_pad",
                f"{c} pad",
                Region(angle=(40.0, 140.0)),
                color=c,
                margin=0.03,
                arms=arms,
            )
        patch = draft.draw_reading(PAD_COLORS)
        draft.place(
            "patch_block",
            "gray_block",
            "gray block",
            Region(r=inspection.INSPECT_R, angle=(40.0, 140.0)),
            patch_color=patch,
            margin=0.04,
            arms=arms,
        )
        draft.params["patch_color"] = patch

    def search_targets(self, scene):
        return [scene.objects.index("gray_block"), scene.objects.index(f"{scene.params['patch_color']}_pad")]

    def evaluate(self, sim, scene, monitor):
        pad = scene.obj(f"{scene.params['patch_color']}_pad")
        return {
            "on_matching_pad": predicates.resting_on(sim, scene.obj("gray_block"), pad),
            "block_released": predicates.released(sim, "gray_block"),
        }

    def read(self, scene, attributes):
        color = attributes["patch_color"]
        return Reading(color, f"{color}_pad", f"place on the {color} pad")
