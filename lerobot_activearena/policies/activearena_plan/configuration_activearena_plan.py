"""Config of ActiveArena-Plan's executor (`oft_subtask_planned_12_ws`, paper App. "ActiveArena-Plan
Architecture"): the OFT head prompted with the planner's subtask and shown the retrieved frames (each
with its state) and the current one. The planner (``activearena_planner``, its own package) is trained
separately; at evaluation the executor loads it (``planner_path``) and runs both."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from lerobot.configs.policies import PreTrainedConfig

from ...annotations.keyframes import STRIDE
from ..activearena_oft.configuration_activearena_oft import ActiveArenaOFTConfig


@PreTrainedConfig.register_subclass("activearena_plan")
@dataclass
class ActiveArenaPlanConfig(ActiveArenaOFTConfig):
    memory: str = "planned"
    # Slots for retrieved frames. The paper's executor memory is uncapped: one frame per subtask
    # keyframe, far fewer than this; only the frames present enter the sequence.
    history: int = 32
    think: str = "none"  # the executor predicts only the action chunk
    # A trained activearena_planner checkpoint (local folder or Hub id); needed at evaluation only.
    planner_path: str | None = None
    uses_planner_memory = True  # memory=planned: the frames its planner retrieves

    def __post_init__(self):
        super().__post_init__()
        if self.memory != "planned":
            raise ValueError(
                f"activearena_plan's memory is the planner's retrievals (memory=planned), got {self.memory!r}"
            )
        if self.n_action_steps != STRIDE:
            raise ValueError(
                f"activearena_plan plans at every chunk on the stride-{STRIDE} grid: n_action_steps must be "
                f"{STRIDE}, got {self.n_action_steps}"
            )
        if self.current_image_pixels is not None:
            raise ValueError(
                "activearena_plan's planner and executor read every frame at one size: leave "
                "--policy.current_image_pixels unset"
            )
        if self.planner_path and Path(self.planner_path).expanduser().is_dir():
            self.planner_path = str(Path(self.planner_path).expanduser().resolve())
