"""Shared shape of the count-and-press tasks (MD): three numbered buttons anywhere in the arms'
band, some objects to count spread over the fan, success = the button of the count pressed.

A subclass places the counted objects for a drawn count (``place_counted``) and says how the
expert counts what it has seen (``count_seen``); buttons, checks and the press come from here.
"""

from __future__ import annotations

from ...expert import routines, view_moves
from ...expert.context import ExpertError
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Subtask, Task
from ..draft import REACH

BUTTONS = (1, 2, 3)
PRESS_SUBTASK = Subtask(
    2, "press_matching_number_button", "localize and press the button corresponding to the inferred count", 1
)


class CountAndPressTask(Task):
    """Base class (not registered: it defines no ``name``)."""

    def place_counted(self, draft, count: int) -> None:
        """Place the objects to count (and any distractors) so that the true count is ``count``."""
        raise NotImplementedError

    def counted_objects(self, scene) -> list[int]:
        """Indices of the objects whose observation the count needs."""
        raise NotImplementedError

    def count_seen(self, ctx, scene, seen: list[int]) -> int:
        """The count the expert infers from the objects it has seen (``seen``: indices)."""
        raise NotImplementedError

    # ---- scene and checks ----------------------------------------------------------------------
    def layout(self, draft):
        count = int(draft.rng.integers(1, 4))
        # Buttons anywhere in the band (not a fixed row): a memorised press lands on the right one
        # only by chance.
        for n in BUTTONS:
            draft.place("button", f"button_{n}", f"button {n}", REACH, number=n, margin=0.02, arms=ARMS)
        self.place_counted(draft, count)
        draft.params["count"] = count

    def search_targets(self, scene):
        return self.counted_objects(scene) + [scene.objects.index(f"button_{scene.params['count']}")]

    def evaluate(self, sim, scene, monitor):
        button = f"button_{scene.params['count']}"
        info = scene.obj(button)
        pressed = monitor.event(
            "pressed",
            predicates.press_moved(sim, info)
            and predicates.pressed_by_either(sim, button, predicates.press_point(sim, info)),
        )
        return {"pressed_matching_button": pressed}

    def failure(self, sim, scene, monitor):
        for n in BUTTONS:
            if n != scene.params["count"] and predicates.press_moved(sim, scene.obj(f"button_{n}")):
                return f"pressed button {n}; the count was {scene.params['count']}"
        return None

    # ---- expert --------------------------------------------------------------------------------
    def expert(self, ctx, scene):
        candidates = [i for i, n in enumerate(ctx.objects) if not n.startswith("button_")]
        with ctx.subtask(1):
            yield from view_moves.sweep_all(ctx, candidates)
            seen = [i for i in candidates if ctx.perception.discovered[i]]
            count = self.count_seen(ctx, scene, seen)
            ctx.notes["count"] = count
            if count not in BUTTONS:
                raise ExpertError(f"counted {count}; there is no such button")
        with ctx.subtask(2):
            button = ctx.idx(f"button_{count}")
            ctx.intent.search_targets = {button}
            side = yield from routines.find_and_face(ctx, button, side=ctx.press_arm)
            yield from routines.press_object(ctx, side, button, depth=0.012)
            yield from routines.finish(ctx, side)
