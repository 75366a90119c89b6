"""check_cola_color (IA): read the colour label on the can's back and stand the can in the area of
that colour.

Task Description:
    A can carries a colour label on its back (a 45 deg arc of radius 0.029 m, facing away from the
    robot); two coloured areas (mats) lie on either side of the fan. Pick the can up, turn it
    until the head camera sees the label, turn it back and stand it inside the area of the
    label's colour.
Randomizations:
    The two area colours (from red / green / blue / yellow / orange / purple) and which one the
    label shows; one area out of the home view on a random side, the other on the other side;
    the can at 40-140 deg, 0.34-0.42 m, label facing outward; can body colour; clutter and (OOD)
    appearance.
Success Conditions:
    can_in_matching_area: the can rests inside the area of its label's colour (inside the mat less
    1 cm); can_upright (tilt <= 15 deg); can_released: no robot contact; all for 8 frames. The
    label counts as task information: a policy that never showed it to the camera fails as DM.
"""

from __future__ import annotations

from ...sim.embodiment import ARMS, other_arm
from ..base import Subtask
from ..draft import HIDDEN, REACH
from ..shapes.inspection import InspectCanTask

AREA_COLORS = ("red", "green", "blue", "yellow", "orange", "purple")


class CheckColaColor(InspectCanTask):
    name = "check_cola_color"
    category = "IA"
    instruction = "Inspect the can's hidden color and place it in the matching area."
    subtasks = (
        Subtask(1, "pick_cola_can", "pick up the can", 0),
        Subtask(2, "inspect_cola_backside_color", "expose and read the backside color label", 1),
        Subtask(3, "restore_cola_after_inspection", "restore the can to a placement-ready pose", 2),
        Subtask(4, "place_can_on_matching_color_area", "select the matching area and place the can", 3),
    )
    max_episode_steps = 270

    def place_areas(self, draft):
        rng = draft.rng
        colors = [str(c) for c in rng.choice(AREA_COLORS, size=2, replace=False)]
        side = draft.side()
        other = other_arm(side)
        draft.place(
            "mat",
            f"{colors[0]}_area",
            f"{colors[0]} area",
            HIDDEN.on(side),
            color_name=colors[0],
            margin=0.03,
            arms=ARMS,
        )
        draft.place(
            "mat",
            f"{colors[1]}_area",
            f"{colors[1]} area",
            REACH.on(other),
            color_name=colors[1],
            margin=0.03,
            arms=ARMS,
        )
        return {"label_kind": "color", "label_color": colors[int(rng.integers(0, 2))]}

    def area_for(self, scene, label):
        return f"{label['label_color']}_area"
