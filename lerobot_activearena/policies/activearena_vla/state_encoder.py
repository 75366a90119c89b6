"""The per-image state token every ActiveArena-VLA head can use."""

from __future__ import annotations

from torch import Tensor, nn


class StateEncoder(nn.Module):
    """One soft token per image from its aligned state (2-layer MLP), plus a learned frame embedding."""

    def __init__(self, state_dim: int, hidden: int, width: int, max_frames: int):
        super().__init__()
        self.mlp = nn.Sequential(nn.Linear(state_dim, hidden), nn.GELU(), nn.Linear(hidden, width))
        self.frame = nn.Embedding(max_frames, width)

    def forward(self, state: Tensor, slot: Tensor) -> Tensor:
        return self.mlp(state) + self.frame(slot)
