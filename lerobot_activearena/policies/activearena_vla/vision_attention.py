"""Qwen3-VL's vision attention over many images of one size as one batched call.

Each image attends only to itself. Without flash-attn's variable-length kernel, Hugging Face's SDPA
path loops over the images: one attention call per image and block, 91 x 24 = 2,184 per forward at
batch 7 with 13 frames a sample, each too small to keep a GPU busy (the training step then waits on
the CPU that launches them). Images of one size are a batch of equal-length sequences: this computes
the same attention with the same weights in one call per block, and falls back to the loop for
mixed sizes or another attention implementation.
"""

from __future__ import annotations

import torch
from torch.nn import functional
from transformers.models.qwen3_vl.modeling_qwen3_vl import Qwen3VLVisionAttention, apply_rotary_pos_emb_vision


class BatchedVisionAttention(Qwen3VLVisionAttention):
    """Qwen3-VL's vision attention (same parameters); equal-size images attend in one SDPA call."""

    def forward(self, hidden_states, cu_seqlens, rotary_pos_emb=None, position_embeddings=None, **kwargs):
        lengths = cu_seqlens[1:] - cu_seqlens[:-1]
        n_images = lengths.numel()
        if (
            self.config._attn_implementation != "sdpa"
            or n_images < 2
            or position_embeddings is None
            or bool((lengths != lengths[0]).any())
        ):
            return super().forward(hidden_states, cu_seqlens, rotary_pos_emb, position_embeddings, **kwargs)
        tokens = hidden_states.shape[0]
        q, k, v = self.qkv(hidden_states).reshape(tokens, 3, self.num_heads, -1).permute(1, 0, 2, 3).unbind(0)
        q, k = apply_rotary_pos_emb_vision(q, k, *position_embeddings)
        # (tokens, heads, dim) -> (images, heads, length, dim)
        q, k, v = (
            t.reshape(n_images, tokens // n_images, self.num_heads, -1).transpose(1, 2) for t in (q, k, v)
        )
        out = functional.scaled_dot_product_attention(q, k, v, scale=self.scaling)
        return self.proj(out.transpose(1, 2).reshape(tokens, -1))


def batch_vision_attention(vlm: torch.nn.Module) -> None:
    """Make every vision block of ``vlm`` attend over equal-size images in one call (in place)."""
    blocks = vlm.model.visual.blocks
    for block in blocks:
        if not isinstance(block.attn, Qwen3VLVisionAttention):
            raise TypeError(f"expected Qwen3-VL's vision attention, got {type(block.attn).__name__}")
        block.attn.__class__ = BatchedVisionAttention
