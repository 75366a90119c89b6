"""Config of ActiveArena-Plan's planner (`oft_subtask_planned_12_ws_planner`, paper App. "ActiveArena-Plan
Architecture"): Qwen3-VL reads the last <= 13 stride-16 frames (no state) and the instruction and
writes ``<think>..</think><subtask>..</subtask><retrieval>[..]</retrieval>``, trained on that text
only. It acts only inside the executor (``activearena_plan``), which loads it at evaluation."""

from __future__ import annotations

from dataclasses import dataclass

from lerobot.configs.policies import PreTrainedConfig

from ..activearena_vla.configuration_activearena_vla import ActiveArenaVLAConfig
from .answers import PLANNER_HISTORY


@PreTrainedConfig.register_subclass("activearena_planner")
@dataclass
class ActiveArenaPlannerConfig(ActiveArenaVLAConfig):
    memory: str = "chunk"  # the stride-16 frames
    history: int = PLANNER_HISTORY
    use_state: bool = False  # the planner sees images and language only
    think: str = "subtask"  # its target names the annotated subtask
    lm_loss_weight: float = 1.0  # its only loss
    plan_max_tokens: int = 128  # greedy decoding budget per answer

    def __post_init__(self):
        super().__post_init__()
        if (self.memory, self.think) != ("chunk", "subtask"):
            raise ValueError(
                "activearena_planner reads the stride-16 frames (memory=chunk) and is trained on the "
                f"subtask annotation (think=subtask); got memory={self.memory!r}, think={self.think!r}"
            )
        if self.lm_loss_weight != 1.0:
            raise ValueError(
                "activearena_planner's only loss is its answer's cross-entropy, so --policy.lm_loss_weight "
                f"(the think loss's weight beside an action loss) has no effect: leave it at 1.0, got {self.lm_loss_weight}"
            )
        if self.plan_max_tokens < 1:
            raise ValueError(f"--policy.plan_max_tokens must be >= 1, got {self.plan_max_tokens}")
