"""ActiveArena-VLA-GR00T: the shared ActiveArena-VLA policy (``activearena_vla``: backbone, memory
bank, state tokens, think loss, evaluation loop) with a flow-matching action head. No action queries enter the backbone's
sequence; the DiT cross-attends to the last-layer states of the images, state tokens and prompt
(not the think span: at inference it is not there), is trained by flow matching and samples a chunk
with a few Euler steps."""

from __future__ import annotations

import torch
from lerobot.utils.constants import ACTION
from torch import Tensor

from ..activearena_vla.helpers import real_steps
from ..activearena_vla.modeling_activearena_vla import THINK, ActiveArenaVLAPolicy
from .configuration_activearena_groot import ActiveArenaGR00TConfig
from .flow_dit import FlowMatchingDiT


class ActiveArenaGR00TPolicy(ActiveArenaVLAPolicy):
    config_class = ActiveArenaGR00TConfig
    name = "activearena_groot"

    def build_action_head(self, width: int) -> None:
        self.dit = FlowMatchingDiT(self.config.dit_config(context_dim=width))

    @property
    def n_queries(self) -> int:
        return 0  # the DiT keeps its own query tokens

    @staticmethod
    def _context_mask(kind: Tensor) -> Tensor:
        return (kind >= 0) & (kind != THINK)

    def decode_actions(self, hidden: Tensor, kind: Tensor) -> Tensor:
        """A sampled (B, chunk, predicted_action_dim) chunk (torch's global RNG: seeded runs repeat)."""
        return self.dit.sample(hidden.float(), self._context_mask(kind))

    def action_loss(self, hidden: Tensor, kind: Tensor, batch: dict[str, Tensor]) -> tuple[Tensor, dict]:
        target = batch[ACTION][..., : self.config.predicted_action_dim].float()
        per = self.dit.loss(
            target,
            hidden.float(),
            self._context_mask(kind),
            reduction="none",
            step_mask=real_steps(batch, target),
        )
        return per, {"flow_loss": float(per.detach().mean())}

    @torch.no_grad()
    def count_head_parameters(self) -> int:
        return sum(p.numel() for p in self.dit.parameters())
