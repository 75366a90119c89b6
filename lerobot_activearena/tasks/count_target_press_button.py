"""MD: count the green blocks scattered over the fan (among blocks of other colours), then press the
button whose number equals the count. The blocks are spread so no single view shows them all."""

from __future__ import annotations

import numpy as np

from ..expert import primitives as P
from ..sim.assets.task_props import BLOCK_COLORS, BUTTON_PRESSED
from .base import SuccessMonitor, Subtask, Task, register_task
from .checks import joint_pos
from .sampling import HIDDEN_REACH

OTHER_COLORS = ("red", "blue", "yellow", "purple", "orange")
BUTTON_SPACING = 0.145  # m between button centres along the arc


class ButtonMonitor(SuccessMonitor):
    """Latches presses; success iff the matching button was pressed and no other button ever was."""

    def __init__(self, task, sim, scene):
        super().__init__(task, sim, scene)
        self.pressed: list[int] = []

    def update(self) -> bool:
        for n in (1, 2, 3):
            if n not in self.pressed and joint_pos(self.sim, f"button_{n}_joint") < BUTTON_PRESSED:
                self.pressed.append(n)
        self.success = self.pressed == [self.scene.params["count"]]
        return self.success


@register_task
class CountTargetPressButton(Task):
    name = "count_target_press_button"
    category = "MD"
    instruction = "Count the target blocks and press the matching button."
    subtasks = (
        Subtask(1, "count_green_target_blocks", "scan targets and distractors and infer the green-block count", 0),
        Subtask(2, "press_matching_number_button", "localize and press the button corresponding to the inferred count", 1),
    )
    max_episode_steps = 450

    def layout(self, draft):
        rng = draft.rng
        count = int(rng.integers(1, 4))
        n_other = int(rng.integers(2, 4))
        # The first green block is out of the initial view: near the right edge or far on either side.
        far_r, far_a = draft.hidden_far()
        hidden_left = far_a[0] > 90 and bool(rng.integers(0, 2))
        r0, a0 = (far_r, far_a) if hidden_left else ((0.36, 0.8), HIDDEN_REACH)
        buttons_at = (55.0, 75.0) if hidden_left else (105.0, 125.0)
        centre = float(rng.uniform(*buttons_at))
        numbers = rng.permutation([1, 2, 3])
        r_b = float(rng.uniform(0.38, 0.43))
        step = float(np.degrees(BUTTON_SPACING / r_b))
        for k, n in enumerate(numbers):
            draft.place("button", f"button_{n}", f"button {n}", r=r_b, angle=centre + (k - 1) * step,
                        number=int(n), margin=0.0, tries=1)
        for k in range(count):
            r, a = (r0, a0) if k == 0 else ((0.36, 0.8), (22.0, 158.0))
            draft.place("block", f"green_block_{k}", f"green block {k + 1}", r=r, angle=a,
                        yaw=float(rng.uniform(-np.pi, np.pi)), rgba=BLOCK_COLORS["green"], half=(0.022,) * 3)
        for k in range(n_other):
            color = OTHER_COLORS[int(rng.integers(0, len(OTHER_COLORS)))]
            draft.place("block", f"{color}_block_{k}", f"{color} block", r=(0.36, 0.8), angle=(22.0, 158.0),
                        yaw=float(rng.uniform(-np.pi, np.pi)), rgba=BLOCK_COLORS[color], half=(0.022,) * 3)
        draft.params["count"] = count

    def search_targets(self, scene):
        greens = [i for i, n in enumerate(scene.objects) if n.startswith("green_block")]
        return greens + [scene.objects.index(f"button_{scene.params['count']}")]

    def reach_targets(self, scene):
        return {i: ("left", "right") for i, n in enumerate(scene.objects) if n.startswith("button")}

    def is_success(self, sim, scene):  # state form (the monitor latches presses)
        return joint_pos(sim, f"button_{scene.params['count']}_joint") < BUTTON_PRESSED

    def monitor(self, sim, scene):
        return ButtonMonitor(self, sim, scene)

    def expert(self, ctx, scene):
        blocks = [i for i, n in enumerate(ctx.objects) if "_block" in n]
        ctx.intent.subtask = 1
        yield from P.sweep_all(ctx, blocks)
        count = sum(1 for i in blocks if ctx.objects[i].startswith("green") and ctx.recorder.discovered[i])
        ctx.notes["counted_green_blocks"] = count
        ctx.intent.subtask = 2
        button = ctx.idx(f"button_{count}")
        ctx.intent.search_targets = {button}
        yield from P.search(ctx, button, center=False)
        side = P.arm_for(ctx.memory[button])
        yield from P.face_for_arm(ctx, ctx.memory[button], side)
        pos, R = ctx.pose(button)
        top = pos + R @ np.asarray(ctx.obj(button).extra["press_point"])
        yield from P.press(ctx, side, top, depth=0.012, targets={button})
        yield from P.retreat(ctx, side)
        yield from P.hold(ctx, 3)
