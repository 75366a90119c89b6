"""Physics health of a running episode. A simulation that blew up (a NaN or diverging state, which
MuJoCo answers by resetting the data with a warning) or an object that left the world ends the
episode as a failure, whatever the policy; the deepest penetration is tracked for demonstrations,
which must also stay under ``PENETRATION_LIMIT``."""

from __future__ import annotations

import mujoco
import numpy as np

PENETRATION_LIMIT = 0.01  # m: deeper contacts disqualify a demonstration
WORLD_RADIUS = 2.5  # m: a free body beyond this (or below WORLD_FLOOR) has left the world
WORLD_FLOOR = 0.3  # m
BLOWUP_WARNINGS = {
    mujoco.mjtWarning.mjWARN_BADQPOS: "bad qpos",
    mujoco.mjtWarning.mjWARN_BADQVEL: "bad qvel",
    mujoco.mjtWarning.mjWARN_BADQACC: "bad qacc",
}


class PhysicsHealth:
    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData):
        self.model, self.data = model, data
        self.free_qadr = [
            model.jnt_qposadr[j] for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE
        ]
        self._warnings = self._warning_counts()
        self.max_penetration = 0.0

    def _warning_counts(self) -> list[int]:
        return [int(self.data.warning[w].number) for w in BLOWUP_WARNINGS]

    def check(self) -> str | None:
        """After a step: what blew up (the episode must end), else None."""
        counts = self._warning_counts()
        blown = [
            name
            for (w, name), n, n0 in zip(BLOWUP_WARNINGS.items(), counts, self._warnings, strict=True)
            if n > n0
        ]
        self._warnings = counts
        if blown:
            return f"the simulation diverged ({', '.join(blown)}; MuJoCo reset its state)"
        d = self.data
        if not (np.isfinite(d.qpos).all() and np.isfinite(d.qvel).all()):
            return "NaN in the simulation state"
        for a in self.free_qadr:
            p = d.qpos[a : a + 3]
            if p[2] < WORLD_FLOOR or np.hypot(p[0], p[1]) > WORLD_RADIUS:
                return f"an object left the world (at {np.round(p, 2).tolist()})"
        if d.ncon:
            self.max_penetration = max(self.max_penetration, float(-d.contact.dist[: d.ncon].min()))
        return None

    def penetration_problem(self, limit: float = PENETRATION_LIMIT) -> str | None:
        if self.max_penetration > limit:
            return f"penetration {self.max_penetration * 1000:.1f} mm"
        return None
