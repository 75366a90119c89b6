"""Shared shape of the A-beside-B tasks (SL): find object A, pick it up, find object B and set A down
on B's instructed side. A and B are drawn per episode and named in the instruction.

A subclass states its row, ``side`` ('left' / 'right', as the robot sees them) and may widen
``movable`` (A's categories: the right-hand task adds the paper's bell, carried 8 cm wide). One of A / B (at
random) starts out of the home view on a random side, the other anywhere in the arms' band, at least
20 cm apart; the spot on B's instructed side is kept free. Success, held 8 frames after both were
seen: ``predicates.beside`` (8-20 cm apart, less than 8 cm apart in distance from the base, in
the instructed angular order), both upright, both released (the robot off them).
Failure: an object off the table (the monitor's, as for every task)."""

from __future__ import annotations

import math

import numpy as np

from ...sim.embodiment import ARMS
from .. import predicates
from ..draft import FAN_ANGLES, SamplingError
from .placing import PickPlaceTask

# Graspable top-down: A. B may also be one the gripper cannot hold (a bell, a loaf).
MOVABLE = {
    "rubiks_cube": "Rubik's cube",
    "mouse": "mouse",
    "stapler": "stapler",
    "wooden_block": "wooden block",
    "coffee_box": "coffee box",
    "toy_car": "toy car",
}
REFERENCES = {**MOVABLE, "bell": "bell", "bread_loaf": "bread"}
# draft.place options of A by category: a carried bell is 8 cm wide (the default 10 cm base does not
# fit the open gripper) and starts at least 37 cm out (held high around its dome, nearer it cannot
# be lifted over B).
CARRIED_OPTIONS = {"bell": {"radius": 0.04, "r": (0.37, 0.45)}}
ROUND = {"bell"}  # carried with the fingers across the line from the robot's base
GAP = 0.14  # m between centres where the expert sets A down (the check allows 8-20 cm)
START_APART = 0.20  # m: A starts at least this far from B (the release: 19 cm)
SPOT_RADIUS = 0.06  # m kept free around the set-down spot


def beside_spot(center_b, side: str, gap: float = GAP) -> np.ndarray:
    """The table point ``gap`` m from B on its ``side``, at B's distance from the robot's base."""
    r, angle = predicates.polar(center_b)
    turn = 2 * math.asin(gap / (2 * r)) * (1 if side == "left" else -1)
    a = math.radians(angle) + turn
    return np.array([r * math.cos(a), r * math.sin(a)])


class PlaceBesideTask(PickPlaceTask):
    side: str
    movable: dict[str, str] = MOVABLE  # A's categories -> their names in the instruction
    obj, dest = "object_a", "object_b"
    lift, hover = 0.15, 0.14  # A is carried over B (up to 12 cm tall: the coffee box)
    instruction_values = {"object": tuple(MOVABLE.values()), "reference": tuple(REFERENCES.values())}

    def layout(self, draft):
        a_cat = str(draft.rng.choice(list(self.movable)))
        b_cat = str(draft.rng.choice([c for c in REFERENCES if c != a_cat]))
        draft.params["object"], draft.params["reference"] = self.movable[a_cat], REFERENCES[b_cat]
        a_region, b_region = self.regions(draft)
        b_region = b_region.on(b_region.side or draft.side())
        # B leaves room for the spot on its instructed side, inside the fan's span.
        room = math.degrees(2 * math.asin(GAP / (2 * b_region.r[0]))) + 4.0
        lo, hi = b_region.angles(b_region.side if b_region.hidden else None)
        lo, hi = (
            (lo, min(hi, FAN_ANGLES[1] - room))
            if self.side == "left"
            else (max(lo, FAN_ANGLES[0] + room), hi)
        )
        if lo > hi:
            raise SamplingError(f"no angle leaves room {self.side} of the {self.dest}")

        def place_a():
            return draft.place(
                a_cat,
                self.obj,
                self.movable[a_cat],
                a_region,
                yaw="random",
                arms=ARMS,
                **CARRIED_OPTIONS.get(a_cat, {}),
            )

        if a_region.hidden:
            _, ra, aa = place_a()
        _, rb, ab = draft.place(
            b_cat, self.dest, REFERENCES[b_cat], b_region, angle=(lo, hi), yaw="random", arms=ARMS
        )
        b_xy = draft.workspace.place(rb, ab)[:2]
        spot = beside_spot(b_xy, self.side)
        if not draft.is_free(spot, SPOT_RADIUS, 0.0):
            raise SamplingError(f"the spot {self.side} of the {self.dest} is taken")
        draft.keep_clear(spot, SPOT_RADIUS)
        if not a_region.hidden:
            _, ra, aa = place_a()
        if np.linalg.norm(draft.workspace.place(ra, aa)[:2] - b_xy) < START_APART:
            raise SamplingError(f"the {self.obj} starts within {START_APART} m of the {self.dest}")

    def grasp_across_for(self, scene):
        return "radial" if scene.obj(self.obj).category in ROUND else self.grasp_across

    def set_down(self, center_b):
        return beside_spot(center_b, self.side)

    def evaluate(self, sim, scene, monitor):
        a, b = scene.obj(self.obj), scene.obj(self.dest)
        return {
            f"{self.obj}_{self.side}_of_{self.dest}": predicates.beside(sim, a, b, self.side),
            f"{self.obj}_upright": predicates.upright(sim, self.obj),
            f"{self.dest}_upright": predicates.upright(sim, self.dest),
            f"{self.obj}_released": predicates.released(sim, self.obj),
            f"{self.dest}_released": predicates.released(sim, self.dest),
        }
