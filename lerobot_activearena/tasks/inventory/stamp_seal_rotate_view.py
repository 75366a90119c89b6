"""stamp_seal_rotate_view (SL): move the seal to the pad of the instructed colour and stamp it.

Task Description:
    Find the seal, pick it up by its handle, find the pad the instruction names elsewhere on the
    fan and set the seal down on it face-first (its stamping face on the pad), then let go.
Randomizations:
    One of seal / pad (random) out of the home view on a random side, the other anywhere in the
    arms' band; seal colour and yaw; the pad's colour from fourteen named colours (the release: 23),
    named in the instruction, 7 x 7 cm as released; clutter and (OOD) appearance.
Success Conditions:
    seal_on_pad: the seal's face rests on the pad's top (its centre and at least half its footprint
    over it); seal_upright: face down, handle up (the release's end state); seal_released; all for
    8 frames, after both were seen; seal_carried: a gripper held it up off everything else at some
    point (a seal pushed onto the thin pad does not count). Failure: the seal off the table.
"""

from __future__ import annotations

from ...sim.assets.colors import MAT_COLORS
from ..base import Subtask
from ..shapes.placing import PickPlaceTask, carried, colored_mat

COLORS = tuple(sorted(MAT_COLORS))


class StampSealRotateView(PickPlaceTask):
    name = "stamp_seal_rotate_view"
    category = "SL"
    instruction = "Move the seal to the beige pad and stamp it."
    instruction_template = "Move the seal to the {mat_color} pad and stamp it."
    instruction_values = {"mat_color": COLORS}
    subtasks = (
        Subtask(1, "pick_seal", "locate and grasp the seal", 0),
        Subtask(2, "stamp_target_pad", "localize the pad and stamp the seal on it", 1),
    )
    max_episode_steps = 188

    obj, dest = "seal", "mat"

    def dest_options(self, draft):
        return colored_mat(draft, COLORS, half=0.035)

    def extra_checks(self, sim, scene, monitor):
        return {"seal_carried": carried(sim, monitor, self.obj)}
