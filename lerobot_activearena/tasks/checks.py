"""State predicates shared by success checks."""

from __future__ import annotations

import math

import numpy as np

from ..sim.simulator import ActiveArenaSim


def body_touches_robot(sim: ActiveArenaSim, body: str) -> bool:
    m, d = sim.model, sim.data
    bid = m.body(body).id
    for c in d.contact[: d.ncon]:
        b1, b2 = m.geom_bodyid[c.geom1], m.geom_bodyid[c.geom2]
        if bid in (b1, b2):
            other = b2 if b1 == bid else b1
            if m.body(other).name.startswith("astribot_"):
                return True
    return False


def upright(sim: ActiveArenaSim, body: str, max_tilt_deg: float = 15.0) -> bool:
    z = sim.data.body(body).xmat.reshape(3, 3)[:, 2]
    return z[2] >= math.cos(math.radians(max_tilt_deg))


def polar(xy) -> tuple[float, float]:
    """(distance from the robot base, workspace angle in degrees)."""
    return float(np.hypot(xy[0], xy[1])), math.degrees(math.atan2(xy[1], xy[0]))


def joint_pos(sim: ActiveArenaSim, joint: str) -> float:
    return float(sim.data.joint(joint).qpos[0])
