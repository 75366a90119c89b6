"""Shared shape of the press tasks (SS: the bell, the stapler, the switch): find a device out of the
home view and press it at its press point (the asset's ``functional.press``) with a closed gripper
until the pressed part travels past its threshold, the device upright and in place.

A subclass states its row and: ``device`` (asset category and object name), ``region`` and
``placement`` (``draft.place`` options: ``yaw`` / ``yaw_jitter``), ``arms`` (the arms that may press:
the instructed one when the instruction names it), ``centered_within`` (the tool centre must be this
close to the press point, horizontally; None: a contact within 2.5 cm is enough), ``press_check``
(the success check's name), ``event`` (the latch's name) and ``depth`` (how far the expert presses).
Failure: the device knocked over or pushed more than 6 cm (irreversible).
"""

from __future__ import annotations

from ...expert import routines
from ...sim.embodiment import ARMS
from .. import predicates
from ..base import Task
from ..draft import Region

IN_PLACE = 0.03  # m: the device stays within this of where it stood (while pressed and after)
PUSHED_AWAY = 0.06  # m: further than this is an irreversible failure


class PressDeviceTask(Task):
    device: str
    region: Region
    placement: dict = {"yaw": "random"}
    arms: tuple[str, ...] = ARMS
    centered_within: float | None = None
    press_check: str = "pressed"
    event: str = "pressed"
    depth: float = 0.01

    def layout(self, draft):
        draft.place(self.device, self.device, self.device, self.region, arms=self.arms, **self.placement)

    def evaluate(self, sim, scene, monitor):
        device = scene.obj(self.device)
        upright = predicates.upright(sim, self.device)
        in_place = predicates.in_place(sim, self.device, IN_PLACE)
        point = predicates.press_point(sim, device)
        by_arm = any(
            predicates.pressed_by(sim, arm, self.device, point, centered_within=self.centered_within)
            for arm in self.arms
        )
        pressed = monitor.event(
            self.event, predicates.press_moved(sim, device) and by_arm and upright and in_place
        )
        return {
            self.press_check: pressed,
            f"{self.device}_upright": upright,
            f"{self.device}_in_place": in_place,
        }

    def failure(self, sim, scene, monitor):
        if predicates.knocked_over(sim, self.device):
            return f"the {self.device} was knocked over"
        if not predicates.in_place(sim, self.device, PUSHED_AWAY):
            return f"the {self.device} was pushed out of place"
        return None

    def expert(self, ctx, scene):
        device = ctx.idx(self.device)
        only = self.arms[0] if len(self.arms) == 1 else None
        with ctx.subtask(1):
            side = yield from routines.find_and_face(ctx, device, side=only)
            yield from routines.press_object(ctx, side, device, depth=self.depth)
            yield from routines.finish(ctx, side)
