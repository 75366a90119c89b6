"""Shared shape of the pick-and-place tasks (SL): find an object, pick it up, find its destination
and set it down there. One of the two (at random) starts out of the home view on a random side, the
other anywhere in the arms' band.

A subclass states its row and: ``obj`` / ``dest`` (object names), ``obj_asset`` / ``dest_asset``
(asset categories; default: the names) or ``obj_choices`` (one category per episode),
``regions(draft)`` (where each goes), ``obj_options(draft)`` / ``dest_options(draft)`` (builder
options drawn per episode), ``obj_yaw`` (``draft.place``'s yaw), ``grasp_across``, ``face_robot``,
``straight_approach`` and the pick / carry heights (``routines.pick_and_place``), ``min_overlap``
or ``placed`` (what resting on the destination means) and ``extra_checks`` (more named checks). Success, held 8 frames after both were seen: the object
rests on the destination's support surface (``predicates.on_support``: footprint-aware), upright,
released. Failure: the object off the table (the monitor's, as for every task)."""

from __future__ import annotations

from ...expert import routines
from ...sim.assets import ASSETS
from ...sim.assets.colors import RELEASE_MAT_COLORS
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Task
from ..draft import HIDDEN, REACH, Region


class PickPlaceTask(Task):
    obj: str
    dest: str
    obj_asset: str | None = None
    dest_asset: str | None = None
    obj_yaw: float | str | None = "random"
    grasp_across: str = "box"
    face_robot: bool = False  # set the object down with its functional.front towards the robot
    lift, approach, hover = 0.12, 0.12, 0.10  # m: routines.pick_and_place's heights
    carry_in: float | None = None  # m from the base the held object is pulled in to (long objects)
    straight_approach = False  # come in to the pick along straight lines (tall objects)
    min_overlap = 0.5  # on_support: the share of the object's footprint over the destination's top
    set_down = None  # f(destination centre) -> table (x, y) to set the object down at (beside it)

    # One object category per episode (category -> its name in the instruction, params['object']);
    # their families are kept out of the clutter, so the object is the only one of its kind.
    obj_choices: dict[str, str] = {}

    def layout(self, draft):
        obj_region, dest_region = self.regions(draft)
        category, label = self.obj_asset or self.obj, self.obj.replace("_", " ")
        if self.obj_choices:
            category = str(draft.rng.choice(list(self.obj_choices)))
            label = draft.params["object"] = self.obj_choices[category]
            draft.clutter_excluded |= {ASSETS[c].family for c in self.obj_choices}
        draft.place(
            category,
            self.obj,
            label,
            obj_region,
            yaw=self.obj_yaw,
            arms=ARMS,
            **self.obj_options(draft),
        )
        draft.place(
            self.dest_asset or self.dest,
            self.dest,
            self.dest.replace("_", " "),
            dest_region,
            arms=ARMS,
            **self.dest_options(draft),
        )

    def regions(self, draft) -> tuple[Region, Region]:
        """Where the object and the destination go: one of them (at random) out of the home view on
        a random side, the other anywhere in the arms' band; a subclass may fix them."""
        obj_hidden = bool(draft.rng.integers(0, 2))
        return (HIDDEN, REACH) if obj_hidden else (REACH, HIDDEN)

    def obj_options(self, draft) -> dict:
        return {}

    def dest_options(self, draft) -> dict:
        return {}

    def evaluate(self, sim, scene, monitor):
        return {
            f"{self.obj}_on_{self.dest}": self.placed(sim, scene),
            f"{self.obj}_upright": predicates.upright(sim, self.obj),
            f"{self.obj}_released": predicates.released(sim, self.obj),
            **self.extra_checks(sim, scene, monitor),
        }

    def placed(self, sim, scene) -> bool:
        """The object rests on the destination (default: on its support surface, ``min_overlap`` of
        its footprint over the top)."""
        return predicates.on_support(sim, scene.obj(self.obj), scene.obj(self.dest), self.min_overlap)

    def extra_checks(self, sim, scene, monitor) -> dict[str, bool]:
        return {}

    def grasp_across_for(self, scene) -> str:
        """``grasp_across`` for this episode's object (a task drawing round and boxy ones differs)."""
        return self.grasp_across

    def expert(self, ctx, scene):
        yield from routines.pick_and_place(
            ctx,
            ctx.idx(self.obj),
            ctx.idx(self.dest),
            grasp_across=self.grasp_across_for(scene),
            face_robot=self.face_robot,
            lift=self.lift,
            approach=self.approach,
            hover=self.hover,
            carry_in=self.carry_in,
            straight_approach=self.straight_approach,
            set_down=self.set_down,
        )


def colored_mat(draft, colors=RELEASE_MAT_COLORS, half: float = 0.05) -> dict:
    """Builder options of a square mat (``half`` m) in a colour drawn from ``colors``, which the
    instruction names (``draft.params['mat_color']``)."""
    color = str(draft.rng.choice(colors))
    draft.params["mat_color"] = color
    return {"color_name": color, "half": (half, half)}


def carried(sim, monitor, body: str) -> bool:
    """Latched: a gripper has held ``body`` up off everything else (carried, not pushed there)."""
    key = f"{body}_carried"
    monitor.state[key] = monitor.state.get(key, False) or predicates.held_by_gripper(sim, body) is not None
    return monitor.state[key]
