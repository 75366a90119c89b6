"""count_color_kinds_press_button (MD): count the distinct block colours and press that button.

Task Description:
    Four blocks in 1-3 distinct colours are spread over the fan (one out of the home view; no
    single view shows them all); three numbered buttons stand in the arms' band. Count how many
    different colours the blocks have, then press the button of that number.
Randomizations:
    Number of colours 1-3 and which palette colours; every chosen colour used at least once, the
    rest of the four blocks repeat them; a random block out of the home view on a random side
    (0.36-0.8 m), the others anywhere at 0.36-0.8 m; yaws random; each button anywhere in the
    arms' band, numbers facing the robot; clutter and (OOD) appearance.
Success Conditions:
    pressed_matching_button: the button of the colour count went below -0.005 m while a closed
    gripper touched it at its press point, after every block was seen. Failure: any other button
    pressed (ends the episode).
"""

from __future__ import annotations

from ...sim.assets.colors import BLOCK_COLORS
from ..base import Subtask
from ..draft import Region
from ..shapes.counting import PRESS_SUBTASK, CountAndPressTask

PALETTE = ("red", "green", "blue", "yellow", "purple")
N_BLOCKS = 4
BLOCK_R = (0.36, 0.8)


def block_color(name: str) -> str:
    return name.split("_")[0]


class CountColorKindsPressButton(CountAndPressTask):
    name = "count_color_kinds_press_button"
    category = "MD"
    instruction = "Count the distinct block colors and press the matching button."
    subtasks = (
        Subtask(1, "count_unique_block_colors", "scan all blocks and infer the number of distinct colors", 0),
        PRESS_SUBTASK,
    )
    max_episode_steps = 150

    def place_counted(self, draft, count):
        rng = draft.rng
        kinds = [str(c) for c in rng.choice(PALETTE, size=count, replace=False)]
        colors = kinds + [kinds[int(rng.integers(0, count))] for _ in range(N_BLOCKS - count)]
        colors = [colors[i] for i in rng.permutation(N_BLOCKS)]
        for k, color in enumerate(colors):
            region = Region(r=BLOCK_R, hidden=True) if k == 0 else Region(r=BLOCK_R)
            draft.place(
                "block",
                f"{color}_block_{k}",
                f"{color} block",
                region,
                yaw="random",
                rgba=BLOCK_COLORS[color],
                half=(0.022,) * 3,
            )
        draft.params["block_colors"] = colors

    def counted_objects(self, scene):
        return [i for i, n in enumerate(scene.objects) if "_block_" in n]

    def count_seen(self, ctx, scene, seen):
        return len({block_color(ctx.objects[i]) for i in seen})
