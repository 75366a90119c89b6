"""The sim-core smoke task: the reference scene (fan table + clutter) with a red can to pick up.

Not one of the paper's 35 tasks; it exercises the full env path (physics, control, rendering,
success) until the task suite is registered.
"""

from __future__ import annotations

from ..sim.scene import reference_scene
from ..sim.simulator import ActiveArenaSim

TARGET = "target_can"


class ReferencePickCan:
    name = "reference_pick_can"
    instruction = "pick up the red can"
    max_episode_steps = 300
    lift_height = 0.10

    def build(self, seed: int):
        return reference_scene(seed, n_objects=24, target=TARGET).compile()

    def on_reset(self, sim: ActiveArenaSim) -> None:
        self._z0 = float(sim.data.body(TARGET).xpos[2])

    def is_success(self, sim: ActiveArenaSim) -> bool:
        return float(sim.data.body(TARGET).xpos[2]) - self._z0 >= self.lift_height


TASKS = {ReferencePickCan.name: ReferencePickCan}
