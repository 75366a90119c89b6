"""check_cola_date (IA): read the production date on the can's back and stand the can in the
"EXPIRED" or the "VALID" area (shelf life 365 days; the instruction gives today's date).

Task Description:
    A can carries its production date on a label on its back (facing away from the robot); a red
    area printed "EXPIRED" and a green area printed "VALID" lie on either side of the fan. Pick the
    can up, turn it where the head camera reads the date, turn it back and stand it in the area of
    its expiry status on the instruction's date.
Randomizations:
    Today's date (2024-01-02 .. 2026-12-31); expired or valid with equal probability, then the age
    (valid: 0-364 days; expired: 366 days or more, production from 2023-01-01); which area is out
    of the home view (random side; the other area on the other side); the can at 40-140 deg,
    0.34-0.42 m, label facing outward; can colour; clutter and (OOD) appearance.
Success Conditions:
    can_in_matching_area: the can rests inside the area of its expiry status (inside the mat less
    1 cm); can_upright (tilt <= 15 deg); can_released: no robot contact; all for 8 frames. The
    label counts as task information: a policy that never showed it to the camera fails as DM.
"""

from __future__ import annotations

import datetime as dt

from ...sim.assets.handheld import DATE_RANGE, SHELF_LIFE_DAYS
from ...sim.embodiment import ARMS, other_arm
from ..base import Subtask
from ..draft import HIDDEN, REACH
from ..shapes.inspection import InspectCanTask

AREAS = {"expired": ("red", "EXPIRED"), "valid": ("green", "VALID")}
TODAY_RANGE = (dt.date(2024, 1, 2), DATE_RANGE[1])


def expired(production: str, today: str) -> bool:
    """Past its shelf life on ``today`` (ISO dates): more than 365 days old."""
    return (dt.date.fromisoformat(today) - dt.date.fromisoformat(production)).days > SHELF_LIFE_DAYS


class CheckColaDate(InspectCanTask):
    name = "check_cola_date"
    category = "IA"
    instruction = "Inspect the production date and sort the can by expiry status."
    subtasks = (
        Subtask(1, "pick_cola_can", "pick up the can", 0),
        Subtask(2, "inspect_cola_backside_date", "expose and read the production-date label", 1),
        Subtask(3, "restore_cola_after_inspection", "restore the can to a placement-ready pose", 2),
        Subtask(
            4,
            "place_cola_by_expiry",
            "infer expiry status, localize the corresponding area, and place the can",
            3,
        ),
    )
    max_episode_steps = 280
    fine_print = True

    def instruction_for(self, params):
        return (
            f"{self.instruction} Today is {params['today']}; a can expires {SHELF_LIFE_DAYS} days after "
            "its production date."
        )

    def place_areas(self, draft):
        rng = draft.rng
        today = TODAY_RANGE[0] + dt.timedelta(
            days=int(rng.integers(0, (TODAY_RANGE[1] - TODAY_RANGE[0]).days + 1))
        )
        is_expired = bool(rng.integers(0, 2))
        if is_expired:
            oldest = (today - DATE_RANGE[0]).days
            age = int(rng.integers(SHELF_LIFE_DAYS + 1, oldest + 1))
        else:
            age = int(rng.integers(0, SHELF_LIFE_DAYS))
        production = (today - dt.timedelta(days=age)).isoformat()
        draft.params["today"] = today.isoformat()
        draft.params["expired"] = is_expired
        side = draft.side()
        other = other_arm(side)
        order = list(AREAS) if rng.integers(0, 2) else list(AREAS)[::-1]
        for status, region in zip(order, (HIDDEN.on(side), REACH.on(other)), strict=True):
            color, text = AREAS[status]
            draft.place(
                "mat",
                f"{status}_area",
                f"{status} area",
                region,
                color_name=color,
                text=text,
                margin=0.03,
                arms=ARMS,
            )
        return {"label_kind": "date", "date": production}

    def area_for(self, scene, label):
        return "expired_area" if expired(label["production_date"], scene.params["today"]) else "valid_area"
