"""count_target_press_button (MD): count the green blocks and press the button of that number.

Task Description:
    1-3 green blocks and 2-3 blocks of other colours are spread over the fan (no single view shows
    every green block); three numbered buttons stand in the arms' band. Count the green blocks,
    then press the button whose number is the count.
Randomizations:
    Count 1-3; the first green block out of the home view on a random side (0.36-0.8 m), the others
    anywhere at 0.36-0.8 m; other colours random; each button anywhere in the arms' band
    (0.34-0.45 m, 20-160 deg), numbers facing the robot; clutter and (OOD) appearance.
Success Conditions:
    pressed_matching_button: button <count>'s cap went below -0.005 m (paper's threshold) while a
    closed gripper touched it within 2.5 cm of its press point. Failure: any other button pressed
    (irreversible: ends the episode).
"""

from __future__ import annotations

from ...expert import primitives as P
from ...expert import routines as R
from ...expert.context import ExpertError
from ...sim.assets.task_props import BLOCK_COLORS, BUTTON_PRESSED
from .. import predicates as Pr
from ..base import Subtask, Task
from ..draft import REACH, Region

OTHER_COLORS = ("red", "blue", "yellow", "purple", "orange")
BLOCK_R = (0.36, 0.8)
ARMS = ("left", "right")


class CountTargetPressButton(Task):
    name = "count_target_press_button"
    category = "MD"
    instruction = "Count the target blocks and press the matching button."
    subtasks = (
        Subtask(1, "count_green_target_blocks", "scan targets and distractors and infer the green-block count", 0),
        Subtask(2, "press_matching_number_button", "localize and press the button corresponding to the inferred count", 1),
    )
    max_episode_steps = 152

    def layout(self, draft):
        rng = draft.rng
        count = int(rng.integers(1, 4))
        # Buttons anywhere in the band (not a fixed row): a memorised press lands on the right one
        # only by chance.
        for n in (1, 2, 3):
            draft.place("button", f"button_{n}", f"button {n}", REACH, number=n, margin=0.02, arms=ARMS)
        for k in range(count):
            region = Region(r=BLOCK_R, hidden=True) if k == 0 else Region(r=BLOCK_R)
            draft.place("block", f"green_block_{k}", f"green block {k + 1}", region, yaw="random",
                        rgba=BLOCK_COLORS["green"], half=(0.022,) * 3)
        for k in range(int(rng.integers(2, 4))):
            color = OTHER_COLORS[int(rng.integers(0, len(OTHER_COLORS)))]
            draft.place("block", f"{color}_block_{k}", f"{color} block", Region(r=BLOCK_R), yaw="random",
                        rgba=BLOCK_COLORS[color], half=(0.022,) * 3)
        draft.params["count"] = count

    def search_targets(self, scene):
        greens = [i for i, n in enumerate(scene.objects) if n.startswith("green_block")]
        return greens + [scene.objects.index(f"button_{scene.params['count']}")]

    def evaluate(self, sim, scene, monitor):
        button = f"button_{scene.params['count']}"
        point = Pr.body_point(sim, button, scene.obj(button).extra["press_point"])
        pressed = monitor.event("pressed", Pr.joint_below(sim, f"{button}_joint", BUTTON_PRESSED)
                                and Pr.pressed_by_either(sim, button, point))
        return {"pressed_matching_button": pressed}

    def failure(self, sim, scene, monitor):
        for n in (1, 2, 3):
            if n != scene.params["count"] and Pr.joint_below(sim, f"button_{n}_joint", BUTTON_PRESSED):
                return f"pressed button {n}; the count was {scene.params['count']}"
        return None

    def expert(self, ctx, scene):
        blocks = [i for i, n in enumerate(ctx.objects) if "_block" in n]
        with ctx.subtask(1):
            yield from P.sweep_all(ctx, blocks)
            count = sum(1 for i in blocks if ctx.objects[i].startswith("green") and ctx.recorder.discovered[i])
            ctx.notes["counted_green_blocks"] = count
            if count == 0:
                raise ExpertError("no green block was seen")
        with ctx.subtask(2):
            button = ctx.idx(f"button_{count}")
            ctx.intent.search_targets = {button}
            side = yield from R.find_and_face(ctx, button)
            yield from R.press_object(ctx, side, button, depth=0.012)
            yield from R.finish(ctx, side)
