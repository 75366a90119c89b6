"""What the head camera sees now and has seen so far: the perception memory that the success
monitor, the expert and the annotation writer read (one ``observe()`` per control step)."""

from __future__ import annotations

import numpy as np

from .simulator import ActiveArenaSim


class PerceptionMemory:
    def __init__(self, sim: ActiveArenaSim, n_objects: int):
        self.sim, self.n = sim, n_objects
        self.visible = np.zeros(n_objects, bool)  # registered objects visible in the current image
        self.discovered = np.zeros(n_objects, bool)  # ... visible in some image so far
        self.uv = -np.ones((n_objects, 2))  # normalised image centre of each visible object

    def observe(self) -> None:
        vis = self.sim.visibility()
        self.visible = vis.visible[: self.n].copy()
        self.uv = vis.uv_norm[: self.n].copy()
        self.discovered |= self.visible
