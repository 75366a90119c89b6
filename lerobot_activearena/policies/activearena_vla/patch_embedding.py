"""Qwen3-VL's patch embedding as one matrix product.

The vision tower embeds each patch with a ``Conv3d`` whose kernel equals its stride, applied to
patches the image processor has already cut out: the same arithmetic as a linear layer over the
flattened patch. PyTorch's CPU convolution is slow at this shape (its backward took 40 % of a
small-VLA training step at 192 x 256); the linear form computes the same result with the same
weights, so checkpoints and the Hugging Face model are unchanged.
"""

from __future__ import annotations

import torch
from torch.nn import functional
from transformers.models.qwen3_vl.modeling_qwen3_vl import Qwen3VLVisionPatchEmbed


class LinearPatchEmbed(Qwen3VLVisionPatchEmbed):
    """Qwen3-VL's patch embedding (same parameters) computed as a linear layer."""

    def forward(self, hidden_states: torch.Tensor) -> torch.Tensor:
        weight = self.proj.weight
        flat = hidden_states.reshape(-1, weight[0].numel()).to(weight.dtype)
        return functional.linear(flat, weight.reshape(self.embed_dim, -1), self.proj.bias)


def patch_embed_as_linear(vlm: torch.nn.Module) -> None:
    """Make ``vlm``'s vision patch embedding run as a linear layer (in place; weights untouched)."""
    embed = vlm.model.visual.patch_embed
    if not isinstance(embed, Qwen3VLVisionPatchEmbed):
        raise TypeError(f"expected Qwen3-VL's patch embedding, got {type(embed).__name__}")
    embed.__class__ = LinearPatchEmbed
