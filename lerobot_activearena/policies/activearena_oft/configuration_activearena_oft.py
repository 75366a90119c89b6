"""Config of ActiveArena-VLA-OFT (the paper's ten OFT runs and ActiveArena-Fixed): the shared
ActiveArena-VLA fields plus the OFT head, 16 action queries regressed by an MLPResNet with L1."""

from __future__ import annotations

from dataclasses import dataclass

from lerobot.configs.policies import PreTrainedConfig

from ..activearena_vla.configuration_activearena_vla import ActiveArenaVLAConfig


@PreTrainedConfig.register_subclass("activearena_oft")
@dataclass
class ActiveArenaOFTConfig(ActiveArenaVLAConfig):
    supports_subtask_memory = True  # memory=subtask: frames where its own decoded subtask changes
    head_blocks: int = 2
    head_hidden_mult: int = 2  # MLPResNet hidden = 2 x VLM width (2048 -> 4096 for the 2B model)
    # The <think> span before the action queries instead of after them: the actions read it (trained on
    # the annotated target; at evaluation the policy first decodes its own span greedily, then acts on it)
    think_first: bool = False

    def __post_init__(self):
        super().__post_init__()
        if self.think_first and self.think == "none":
            raise ValueError(
                "--policy.think_first=true puts the <think> span before the action queries, so it needs "
                "a think target: set --policy.think (subtask or decision)"
            )
        if self.think_first and self.memory == "subtask":
            raise ValueError(
                "--policy.think_first=true does not combine with memory=subtask (that memory decodes its "
                "subtask from the pass that yields the chunk, with the span after the queries): use "
                "memory=chunk, or think_first=false"
            )
