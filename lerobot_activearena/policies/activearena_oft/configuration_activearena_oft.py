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
