"""Shared shape of the can-inspection tasks (IA): a can whose label (a colour, a production date)
faces away from the robot; pick it up, turn the label to the head camera, read it, turn the can
back and stand it inside the area the label implies.

A subclass places the areas and chooses the label (``place_areas`` returns the labelled can's
asset parameters), and maps what the expert read to the area (``area_for``).
"""

from __future__ import annotations

from ...expert import inspection, routines, skills
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Task
from ..draft import Region

CAN = "cola_can"


class InspectCanTask(Task):
    """Base class (not registered: it defines no ``name``)."""

    fine_print = False  # the label must be read in detail: the expert turns it where the view is frontal

    def place_areas(self, draft) -> dict:
        """Place the areas (mats); return the ``labeled_can`` parameters (label kind and content)."""
        raise NotImplementedError

    def area_for(self, scene, label: dict) -> str:
        """The name of the area a can with this label belongs in (``label``: the asset's extra)."""
        raise NotImplementedError

    def layout(self, draft):
        label = self.place_areas(draft)
        # Label faces outward (yaw None: body +x radially out, a little jitter): unreadable at home.
        draft.place(
            "labeled_can",
            CAN,
            "cola can",
            Region(r=inspection.INSPECT_R, angle=(40.0, 140.0)),
            margin=0.04,
            arms=ARMS,
            **label,
        )
        draft.params["label"] = label

    def information_faces(self, scene):
        return [CAN]

    def search_targets(self, scene):
        return [
            scene.objects.index(CAN),
            scene.objects.index(self.area_for(scene, scene.obj(CAN).attributes)),
        ]

    def evaluate(self, sim, scene, monitor):
        area = scene.obj(self.area_for(scene, scene.obj(CAN).attributes))
        return {
            "can_in_matching_area": predicates.resting_on(
                sim, CAN, area.name, area.half_extents[:2], area.functional.support.top
            ),
            "can_upright": predicates.upright(sim, CAN),
            "can_released": predicates.released(sim, CAN),
        }

    def expert(self, ctx, scene):
        can = ctx.idx(CAN)
        with ctx.subtask(1):
            turn = yield from inspection.pick_for_inspection(ctx, can, fine_print=self.fine_print)
        with ctx.subtask(2):
            yield from inspection.show_hidden_face(ctx, turn, can)
            label = ctx.obj(can).attributes  # read off the visible label
            area = self.area_for(scene, label)
            reading = {k: v for k, v in label.items() if k in ("label_color", "production_date")}
            ctx.notes["observed_label"] = reading
            inspection.record_reading(ctx, can, reading, f"place in the {area.replace('_', ' ')}")
        with ctx.subtask(3):
            yield from inspection.restore_pose(ctx, turn, can)
        with ctx.subtask(4):
            target = ctx.idx(area)
            yield from routines.find_and_face(ctx, target, turn.side)
            skills.start_action(ctx, {can, target})
            ctx.intent.carried = {can}
            yield from skills.place(
                ctx, turn.side, can, ctx.center(target)[:2], ctx.top_z(target), yaw_free=True
            )
            yield from routines.finish(ctx, turn.side)
