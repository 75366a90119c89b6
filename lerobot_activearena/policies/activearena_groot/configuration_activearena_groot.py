"""Config of ActiveArena-VLA-GR00T (`gr00t_subtask_action_12_ws`): the OFT run's backbone, memory,
state tokens, ``<think>`` co-training and optimiser (the shared ``activearena_vla`` fields), with the
action queries and MLPResNet replaced by a flow-matching DiT head that cross-attends to the
backbone's hidden states (``flow_dit``)."""

from __future__ import annotations

from dataclasses import dataclass

from lerobot.configs.policies import PreTrainedConfig

from ..activearena_vla.configuration_activearena_vla import ActiveArenaVLAConfig
from .flow_dit import DiTConfig


@PreTrainedConfig.register_subclass("activearena_groot")
@dataclass
class ActiveArenaGR00TConfig(ActiveArenaVLAConfig):
    # DiT-B (paper / release): 16 blocks, 12 heads x 64 = 768 wide, 32 learned query tokens, output 1024,
    # action decoder MLP 1024; Beta(1.5, 1) flow time, 8 noise repeats, 4 Euler steps at inference.
    dit_width: int = 768
    dit_depth: int = 16
    dit_heads: int = 12
    dit_queries: int = 32
    dit_out_dim: int = 1024
    decoder_width: int = 1024
    dit_dropout: float = 0.2
    noise_repeats: int = 8
    inference_steps: int = 4

    def dit_config(self, context_dim: int) -> DiTConfig:
        """The head's sizes for a backbone of hidden size ``context_dim`` (validated there)."""
        return DiTConfig(
            action_dim=self.predicted_action_dim,
            horizon=self.chunk_size,
            context_dim=context_dim,
            width=self.dit_width,
            depth=self.dit_depth,
            heads=self.dit_heads,
            queries=self.dit_queries,
            out_dim=self.dit_out_dim,
            decoder_width=self.decoder_width,
            dropout=self.dit_dropout,
            noise_repeats=self.noise_repeats,
            inference_steps=self.inference_steps,
        )

    def __post_init__(self):
        super().__post_init__()
        self.dit_config(context_dim=1)  # bad sizes fail at parse time, not after the backbone loads
