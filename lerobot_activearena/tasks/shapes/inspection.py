"""Shared shape of the inspection tasks (IA): objects whose information (a gray block's back patch, a
can's colour or date label) faces away from the robot. For each, nearest first: pick it up, turn
the hidden face to the head camera and read it, optionally turn it back (``restore_before_placing``),
then find the destination the reading names and set the object down there.

A subclass lays out the scene, names the inspected objects (``inspected``), maps an object's
attributes to a ``Reading`` (``read``) and, for shared destinations, where on it the object goes
(``place_spot``). Its ``evaluate`` names the checks. ``InspectCanTask`` is the can tasks' row
template: one labelled can, its areas placed by ``place_areas``, its area chosen by ``area_for``.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...expert import inspection, motion, routines, skills
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Task
from ..draft import Region

CAN = "cola_can"


@dataclass(frozen=True)
class Reading:
    """What the expert read off a hidden face: the ``value`` (kept in its notes and annotations),
    the ``destination`` object it implies and the ``text`` of the next step."""

    value: object
    destination: str
    text: str


class InspectAndPlaceTask(Task):
    """Base class (not registered: it defines no ``name``). Subtasks per inspected object: pick,
    inspect, (restore), place."""

    inspected: tuple[str, ...] = ()
    restore_before_placing = False
    fine_print = False  # the label must be read in detail: the expert turns it where the view is frontal
    note = "observed_color"  # ctx.notes key of a reading (suffixed _k with several objects)

    def read(self, scene, attributes: dict) -> Reading:
        raise NotImplementedError

    def place_spot(self, ctx, scene, dest: int, reading: Reading, placed_before: int):
        """Where on ``dest`` the object goes (xy), ``placed_before`` objects already on it."""
        return ctx.center(dest)[:2]

    def information_faces(self, scene):
        return list(self.inspected)

    def expert(self, ctx, scene):
        todo = [ctx.idx(n) for n in self.inspected]
        single = len(todo) == 1
        placed: dict[int, int] = {}  # destination -> objects already placed on it
        first = 1  # the object's first subtask
        for k in range(len(todo)):
            with ctx.subtask(first):
                obj = routines.nearest_known(ctx, todo)
                todo.remove(obj)
                turn = yield from inspection.pick_for_inspection(ctx, obj, fine_print=self.fine_print)
            with ctx.subtask(first + 1):
                yield from inspection.show_hidden_face(ctx, turn, obj)
                reading = self.read(scene, ctx.obj(obj).attributes)  # read off the visible face
                ctx.notes[self.note if single else f"{self.note}_{k}"] = reading.value
                inspection.record_reading(ctx, obj, reading.value, reading.text)
            if self.restore_before_placing:
                with ctx.subtask(first + 2):
                    yield from inspection.restore_pose(ctx, turn, obj)
            last = first + 2 + self.restore_before_placing
            with ctx.subtask(last):
                dest = ctx.idx(reading.destination)
                yield from routines.find_and_face(ctx, dest, turn.side)
                spot = self.place_spot(ctx, scene, dest, reading, placed.get(dest, 0))
                placed[dest] = placed.get(dest, 0) + 1
                skills.start_action(ctx, {obj, dest})
                ctx.intent.carried = {obj}
                yield from skills.place(ctx, turn.side, obj, spot, ctx.top_z(dest), yaw_free=True)
                yield from skills.retreat(ctx, turn.side)
                if single:
                    yield from motion.hold(ctx, 3)
            first = last + 1
        if not single:
            yield from motion.hold(ctx, 3)


class InspectCanTask(InspectAndPlaceTask):
    """Base class of the can tasks: a can whose label faces away; read it, turn the can back and
    stand it inside the area the label implies. A row places the areas and chooses the label
    (``place_areas`` returns the labelled can's asset parameters) and maps a label to its area
    (``area_for``)."""

    inspected = (CAN,)
    restore_before_placing = True
    note = "observed_label"

    def place_areas(self, draft) -> dict:
        """Place the areas (mats); return the ``labeled_can`` parameters (label kind and content)."""
        raise NotImplementedError

    def area_for(self, scene, label: dict) -> str:
        """The name of the area a can with this label belongs in (``label``: the asset's extra)."""
        raise NotImplementedError

    def read(self, scene, attributes):
        area = self.area_for(scene, attributes)
        value = {k: v for k, v in attributes.items() if k in ("label_color", "production_date")}
        return Reading(value, area, f"place in the {area.replace('_', ' ')}")

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

    def search_targets(self, scene):
        return [
            scene.objects.index(CAN),
            scene.objects.index(self.area_for(scene, scene.obj(CAN).attributes)),
        ]

    def evaluate(self, sim, scene, monitor):
        area = scene.obj(self.area_for(scene, scene.obj(CAN).attributes))
        return {
            "can_in_matching_area": predicates.resting_on(sim, scene.obj(CAN), area),
            "can_upright": predicates.upright(sim, CAN),
            "can_released": predicates.released(sim, CAN),
        }
