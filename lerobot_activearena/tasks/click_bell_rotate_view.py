"""SS: find the bell (placed outside the initial view) and press its top centre with the left arm."""

from __future__ import annotations

import numpy as np

from ..expert import primitives as P
from ..sim.assets.task_props import BELL_PRESSED
from .base import SuccessMonitor, Subtask, Task, register_task
from .sampling import HIDDEN_REACH
from .checks import joint_pos


class BellMonitor(SuccessMonitor):
    """Success latches once the plunger went below the pressed threshold."""

    def update(self) -> bool:
        if joint_pos(self.sim, "bell_plunger_joint") < BELL_PRESSED:
            self.success = True
        return self.success


@register_task
class ClickBellRotateView(Task):
    name = "click_bell_rotate_view"
    category = "SS"
    instruction = "Press the bell's top center using the left arm."
    subtasks = (Subtask(1, "_click_bell", "locate the bell and press its top center", 0),)
    max_episode_steps = 300

    def layout(self, draft):
        draft.place("bell", "bell", "bell", angle=HIDDEN_REACH, yaw=float(draft.rng.uniform(-np.pi, np.pi)))

    def reach_targets(self, scene):
        return {scene.objects.index("bell"): ("left",)}

    def is_success(self, sim, scene):
        return joint_pos(sim, "bell_plunger_joint") < BELL_PRESSED

    def monitor(self, sim, scene):
        return BellMonitor(self, sim, scene)

    def expert(self, ctx, scene):
        bell = ctx.idx("bell")
        yield from P.search(ctx, bell, center=False)
        yield from P.face_for_arm(ctx, ctx.memory[bell], "left")
        pos, R = ctx.pose(bell)
        top = pos + R @ np.asarray(ctx.obj(bell).extra["press_point"])
        yield from P.press(ctx, "left", top, depth=0.007, targets={bell})
        yield from P.retreat(ctx, "left")
        yield from P.hold(ctx, 3)
