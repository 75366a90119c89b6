"""Configs of ActiveArena-Plan (`oft_subtask_planned_12_ws`, paper App. "ActiveArena-Plan
Architecture"): two models trained separately. ``activearena_planner`` reads the last <= 13
stride-16 frames (no state) and the instruction and writes ``<think>..</think><subtask>..</subtask>
<retrieval>[..]</retrieval>``; ``activearena_plan`` is the OFT executor, prompted with the subtask and
shown the retrieved frames (each with its state) and the current one. At evaluation the executor
loads its planner (``planner_path``) and runs both."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from lerobot.configs.policies import PreTrainedConfig

from ...annotations.keyframes import STRIDE
from ..activearena_oft.configuration_activearena_oft import ActiveArenaOFTConfig
from ..activearena_vla.configuration_activearena_vla import ActiveArenaVLAConfig
from .planning import PLANNER_HISTORY


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
        if self.planner_path and Path(self.planner_path).expanduser().is_dir():
            self.planner_path = str(Path(self.planner_path).expanduser().resolve())
