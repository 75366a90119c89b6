"""ActiveArena-VLA-OFT: the shared ActiveArena-VLA policy with the OFT head: 16 action-query positions
after the prompt feed an MLPResNet that regresses a 16 x 18 chunk with L1 (the ``<think>`` span after
the queries is trained with next-token loss, weight 0.1)."""

from __future__ import annotations

import torch
from lerobot.utils.constants import ACTION
from torch import Tensor, nn

from ..activearena_vla.helpers import real_steps
from ..activearena_vla.modeling_activearena_vla import QUERY, ActiveArenaVLAPolicy
from .configuration_activearena_oft import ActiveArenaOFTConfig
from .heads import MLPResNet


class ActiveArenaOFTPolicy(ActiveArenaVLAPolicy):
    config_class = ActiveArenaOFTConfig
    name = "activearena_oft"

    def build_action_head(self, width: int) -> None:
        self.action_queries = nn.Parameter(torch.randn(self.config.chunk_size, width) * 0.02)
        self.head = MLPResNet(
            width,
            self.config.head_hidden_mult * width,
            self.config.predicted_action_dim,
            self.config.head_blocks,
        )

    @property
    def n_queries(self) -> int:
        """Action query tokens after the prompt: one per chunk step."""
        return self.config.chunk_size

    def decode_actions(self, hidden: Tensor, kind: Tensor) -> Tensor:
        """The (B, chunk, predicted_action_dim) prediction from the last-layer states at the action queries."""
        return self.head(hidden[kind == QUERY].view(kind.shape[0], self.config.chunk_size, -1).float())

    def action_loss(self, hidden: Tensor, kind: Tensor, batch: dict[str, Tensor]) -> tuple[Tensor, dict]:
        """Per-sample L1 over the chunk's real (not padded) steps."""
        pred = self.decode_actions(hidden, kind).float()
        target = batch[ACTION][..., : self.config.predicted_action_dim]
        keep = real_steps(batch, target)
        l1 = (pred - target).abs().mean(-1)
        l1 = (l1 * keep).sum(-1) / keep.sum(-1).clamp(min=1)
        return l1, {"l1_loss": float(l1.detach().mean())}
