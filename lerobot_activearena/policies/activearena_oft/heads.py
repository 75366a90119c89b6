"""The OFT action head (an MLPResNet over the action-query hidden states) and the state encoder."""

from __future__ import annotations

from torch import Tensor, nn


class ResidualBlock(nn.Module):
    def __init__(self, width: int):
        super().__init__()
        self.net = nn.Sequential(nn.LayerNorm(width), nn.Linear(width, width), nn.ReLU())

    def forward(self, x: Tensor) -> Tensor:
        return x + self.net(x)


class MLPResNet(nn.Module):
    """in -> hidden, ``blocks`` residual blocks, -> out (OpenVLA-OFT's L1 regression head)."""

    def __init__(self, in_dim: int, hidden: int, out_dim: int, blocks: int = 2):
        super().__init__()
        self.inp = nn.Sequential(nn.LayerNorm(in_dim), nn.Linear(in_dim, hidden), nn.ReLU())
        self.blocks = nn.Sequential(*[ResidualBlock(hidden) for _ in range(blocks)])
        self.out = nn.Sequential(nn.LayerNorm(hidden), nn.Linear(hidden, out_dim))

    def forward(self, x: Tensor) -> Tensor:
        return self.out(self.blocks(self.inp(x)))


class StateEncoder(nn.Module):
    """One soft token per image from its aligned state (2-layer MLP), plus a learned frame embedding."""

    def __init__(self, state_dim: int, hidden: int, width: int, max_frames: int):
        super().__init__()
        self.mlp = nn.Sequential(nn.Linear(state_dim, hidden), nn.GELU(), nn.Linear(hidden, width))
        self.frame = nn.Embedding(max_frames, width)

    def forward(self, state: Tensor, slot: Tensor) -> Tensor:
        return self.mlp(state) + self.frame(slot)
