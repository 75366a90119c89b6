"""The GR00T-style flow-matching action head of ActiveArena-VLA's `gr00t_subtask_action_12_ws` run.

A diffusion transformer (DiT) over a sequence of learned query tokens followed by the noisy action
chunk's tokens. Even blocks cross-attend to the backbone's hidden states (the whole prompt, with its
padding mask), odd blocks attend within the sequence; every block is modulated by the flow time
(adaptive LayerNorm). Only the action positions are decoded: DiT output (1024) -> MLP -> 18-D.

Training (flow matching, as the release): time t = (s - min(b, s)) / s with b ~ Beta(1.5, 1) and
s = 0.999 (most samples near noise), the input (1 - t) noise + t action, the target velocity
action - noise, MSE; every sample repeated with fresh noise and time. Inference: forward Euler from
noise (t = 0) to the action (t = 1) in a few steps. Attention is PyTorch's scaled_dot_product_attention.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import torch
import torch.nn.functional as F  # noqa: N812
from torch import Tensor, nn


@dataclass(frozen=True)
class DiTConfig:
    action_dim: int = 18
    horizon: int = 16  # action steps per chunk
    context_dim: int = 2048  # the backbone's hidden size (Qwen3-VL-2B)
    width: int = 768  # DiT-B: 12 heads x 64
    depth: int = 16
    heads: int = 12
    queries: int = 32  # learned tokens before the action tokens
    out_dim: int = 1024  # DiT output size
    decoder_width: int = 1024  # the action decoder MLP's width
    dropout: float = 0.2
    time_buckets: int = 1000  # t is embedded as its bucket index
    noise_s: float = 0.999  # time sampling cut-off
    beta_alpha: float = 1.5  # Beta(alpha, 1): skews t towards noise
    noise_repeats: int = 8  # fresh (noise, t) draws per training sample
    inference_steps: int = 4

    def __post_init__(self):
        if self.width % self.heads:
            raise ValueError(f"width {self.width} must be a multiple of heads {self.heads}")
        if self.inference_steps < 1 or self.noise_repeats < 1:
            raise ValueError("inference_steps and noise_repeats must be >= 1")


def sinusoidal(index: Tensor, dim: int) -> Tensor:
    """(B,) integer time buckets -> (B, dim) sin/cos features."""
    half = dim // 2
    freqs = torch.exp(-math.log(10000.0) * torch.arange(half, device=index.device) / half)
    angles = index.float()[:, None] * freqs[None]
    return torch.cat([angles.sin(), angles.cos()], dim=-1)


class TimeEmbedding(nn.Module):
    def __init__(self, width: int, features: int = 256):
        super().__init__()
        self.features = features
        self.mlp = nn.Sequential(nn.Linear(features, width), nn.SiLU(), nn.Linear(width, width))

    def forward(self, bucket: Tensor) -> Tensor:
        return self.mlp(sinusoidal(bucket, self.features))


class DiTBlock(nn.Module):
    """AdaLN (scale, shift from the time embedding) -> attention (cross to ``context`` when it has a
    ``context_dim``, else self) -> residual; LayerNorm -> GELU MLP -> residual."""

    def __init__(self, width: int, heads: int, context_dim: int | None, dropout: float):
        super().__init__()
        self.heads, self.cross = heads, context_dim is not None
        self.norm = nn.LayerNorm(width, elementwise_affine=False)
        self.modulation = nn.Linear(width, 2 * width)
        kv_dim = context_dim if context_dim is not None else width
        self.q = nn.Linear(width, width)
        self.k = nn.Linear(kv_dim, width)
        self.v = nn.Linear(kv_dim, width)
        self.o = nn.Linear(width, width)
        self.drop = nn.Dropout(dropout)
        self.ff_norm = nn.LayerNorm(width)
        self.ff = nn.Sequential(
            nn.Linear(width, 4 * width),
            nn.GELU(approximate="tanh"),
            nn.Dropout(dropout),
            nn.Linear(4 * width, width),
        )

    def _split(self, x: Tensor) -> Tensor:
        b, n, _ = x.shape
        return x.view(b, n, self.heads, -1).transpose(1, 2)

    def forward(self, x: Tensor, temb: Tensor, context: Tensor, context_mask: Tensor | None) -> Tensor:
        scale, shift = self.modulation(F.silu(temb)).chunk(2, dim=-1)
        h = self.norm(x) * (1 + scale[:, None]) + shift[:, None]
        kv, mask = (context, context_mask) if self.cross else (h, None)
        attn_mask = None if mask is None else mask[:, None, None, :].bool()  # (B, 1, 1, S): True = attend
        a = F.scaled_dot_product_attention(
            self._split(self.q(h)),
            self._split(self.k(kv)),
            self._split(self.v(kv)),
            attn_mask=attn_mask,
            dropout_p=self.drop.p if self.training else 0.0,
        )
        x = x + self.drop(self.o(a.transpose(1, 2).flatten(2)))
        return x + self.ff(self.ff_norm(x))


class FlowMatchingDiT(nn.Module):
    """``loss(actions, context, mask)`` for training, ``sample(context, mask)`` at inference; actions
    are (B, horizon, action_dim) normalised chunks, context the backbone's (B, S, context_dim) hidden
    states with a (B, S) mask (1 = a real token)."""

    def __init__(self, config: DiTConfig | None = None):
        super().__init__()
        c = self.config = config or DiTConfig()
        self.time = TimeEmbedding(c.width)
        self.action_in = nn.Sequential(
            nn.Linear(c.action_dim, c.width), nn.SiLU(), nn.Linear(c.width, c.width)
        )
        self.position = nn.Parameter(torch.randn(c.horizon, c.width) * 0.02)
        self.query_tokens = nn.Parameter(torch.randn(c.queries, c.width) * 0.02)
        self.blocks = nn.ModuleList(
            DiTBlock(c.width, c.heads, c.context_dim if k % 2 == 0 else None, c.dropout)
            for k in range(c.depth)
        )
        self.norm_out = nn.LayerNorm(c.width, elementwise_affine=False)
        self.out_modulation = nn.Linear(c.width, 2 * c.width)
        self.proj_out = nn.Linear(c.width, c.out_dim)
        self.decoder = nn.Sequential(
            nn.Linear(c.out_dim, c.decoder_width), nn.GELU(), nn.Linear(c.decoder_width, c.action_dim)
        )

    def velocity(
        self, noisy: Tensor, t: Tensor, context: Tensor, context_mask: Tensor | None = None
    ) -> Tensor:
        """Predicted velocity (B, horizon, action_dim) at flow time ``t`` (B,) in [0, 1]."""
        c = self.config
        bucket = (t * c.time_buckets).long().clamp(0, c.time_buckets - 1)
        temb = self.time(bucket)
        b = noisy.shape[0]
        x = torch.cat([self.query_tokens.expand(b, -1, -1), self.action_in(noisy) + self.position], dim=1)
        for block in self.blocks:
            x = block(x, temb, context, context_mask)
        scale, shift = self.out_modulation(F.silu(temb)).chunk(2, dim=-1)
        x = self.norm_out(x) * (1 + scale[:, None]) + shift[:, None]
        return self.decoder(self.proj_out(x[:, c.queries :]))

    def sample_time(self, n: int, generator: torch.Generator | None = None, device=None) -> Tensor:
        """t = (s - min(b, s)) / s, b ~ Beta(alpha, 1) (inverse CDF: u ** (1 / alpha))."""
        c = self.config
        u = torch.rand(n, generator=generator, device=device)
        b = u ** (1.0 / c.beta_alpha)
        return (c.noise_s - b.clamp(max=c.noise_s)) / c.noise_s

    def loss(
        self,
        actions: Tensor,
        context: Tensor,
        context_mask: Tensor | None = None,
        generator: torch.Generator | None = None,
        reduction: str = "mean",
        step_mask: Tensor | None = None,
    ) -> Tensor:
        """Flow-matching MSE, each sample repeated ``noise_repeats`` times with fresh noise and time;
        ``reduction="none"``: one loss per sample (averaged over its repeats). ``step_mask`` (B,
        horizon): the chunk steps that count (padding past an episode's end does not)."""
        r = self.config.noise_repeats
        act = actions.repeat_interleave(r, dim=0)
        ctx = context.repeat_interleave(r, dim=0)
        mask = None if context_mask is None else context_mask.repeat_interleave(r, dim=0)
        noise = torch.randn(act.shape, generator=generator, device=act.device, dtype=act.dtype)
        t = self.sample_time(act.shape[0], generator, act.device).to(act.dtype)
        noisy = (1 - t)[:, None, None] * noise + t[:, None, None] * act
        err = F.mse_loss(self.velocity(noisy, t, ctx, mask), act - noise, reduction="none").mean(dim=2)
        if step_mask is None:
            per = err.mean(dim=1)
        else:
            keep = step_mask.repeat_interleave(r, dim=0).to(err.dtype)
            per = (err * keep).sum(dim=1) / keep.sum(dim=1).clamp(min=1)
        per = per.view(-1, r).mean(dim=1)
        return per.mean() if reduction == "mean" else per

    @torch.no_grad()
    def sample(
        self,
        context: Tensor,
        context_mask: Tensor | None = None,
        generator: torch.Generator | None = None,
        steps: int | None = None,
    ) -> Tensor:
        """Forward Euler from noise (t = 0) to an action chunk (t = 1)."""
        c = self.config
        steps = steps or c.inference_steps
        shape = (context.shape[0], c.horizon, c.action_dim)
        x = torch.randn(shape, generator=generator, device=context.device, dtype=context.dtype)
        dt = 1.0 / steps
        for k in range(steps):
            t = torch.full((shape[0],), k * dt, device=context.device, dtype=context.dtype)
            x = x + dt * self.velocity(x, t, context, context_mask)
        return x
