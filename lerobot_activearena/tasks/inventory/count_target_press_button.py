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

from ...sim.assets.colors import BLOCK_COLORS
from ..base import Subtask
from ..draft import Region
from ..shapes.counting import PRESS_SUBTASK, CountAndPressTask

OTHER_COLORS = ("red", "blue", "yellow", "purple", "orange")
BLOCK_R = (0.36, 0.8)


class CountTargetPressButton(CountAndPressTask):
    name = "count_target_press_button"
    category = "MD"
    instruction = "Count the target blocks and press the matching button."
    subtasks = (
        Subtask(
            1, "count_green_target_blocks", "scan targets and distractors and infer the green-block count", 0
        ),
        PRESS_SUBTASK,
    )
    max_episode_steps = 152

    def place_counted(self, draft, count):
        rng = draft.rng
        for k in range(count):
            region = Region(r=BLOCK_R, hidden=True) if k == 0 else Region(r=BLOCK_R)
            draft.place(
                "block",
                f"green_block_{k}",
                f"green block {k + 1}",
                region,
                yaw="random",
                rgba=BLOCK_COLORS["green"],
                half=(0.022,) * 3,
            )
        for k in range(int(rng.integers(2, 4))):
            color = OTHER_COLORS[int(rng.integers(0, len(OTHER_COLORS)))]
            draft.place(
                "block",
                f"{color}_block_{k}",
                f"{color} block",
                Region(r=BLOCK_R),
                yaw="random",
                rgba=BLOCK_COLORS[color],
                half=(0.022,) * 3,
            )

    def counted_objects(self, scene):
        return [i for i, n in enumerate(scene.objects) if n.startswith("green_block")]

    def count_seen(self, ctx, scene, seen):
        return sum(1 for i in seen if ctx.objects[i].startswith("green_block"))
