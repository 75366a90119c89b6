"""move_pillbottle_pad_rotate_view (SL): move the pill bottle onto the pad.

Task Description:
    Find the pill bottle, pick it up, find the pad elsewhere on the fan and set the bottle down on it.
Randomizations:
    One of bottle / pad (random) out of the home view on a random side, the other anywhere in the
    arms' band (0.34-0.45 m); bottle colour and yaw; pad colour (the instruction names no colour);
    clutter and (OOD) appearance.
Success Conditions:
    pill_bottle_on_pad: the bottle's base rests on the pad's top (its centre and at least half its
    footprint over it); pill_bottle_upright; pill_bottle_released: no robot link touches it; all for
    8 frames, after both were seen. Failure: the bottle off the table.
"""

from __future__ import annotations

from ...sim.assets.colors import BLOCK_COLORS
from ..base import Subtask
from ..shapes.placing import PickPlaceTask


class MovePillbottlePadRotateView(PickPlaceTask):
    name = "move_pillbottle_pad_rotate_view"
    category = "SL"
    instruction = "Move the pill bottle onto the pad."
    subtasks = (
        Subtask(1, "pick_pillbottle", "locate and grasp the pill bottle", 0),
        Subtask(2, "place_pillbottle_on_pad", "localize the pad and place the carried pill bottle on it", 1),
    )
    max_episode_steps = 183

    obj, dest = "pill_bottle", "pad"
    dest_asset = "color_pad"
    grasp_across = "radial"

    def dest_options(self, draft):
        return {
            "half": 0.04,
            "color": str(draft.rng.choice(sorted(BLOCK_COLORS))),
        }  # the release's 8 x 8 cm pad
