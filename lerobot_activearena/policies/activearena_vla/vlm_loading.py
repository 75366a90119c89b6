"""Load the Qwen3-VL parts (model, processor, tokenizer) from ``vlm_path``, a Hugging Face id or a
local folder, with one error that names the fix when it cannot be found."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


def load_from_vlm_path(loader: Callable[..., Any], vlm_path: str, what: str, **kwargs) -> Any:
    try:
        return loader(vlm_path, **kwargs)
    except (OSError, ValueError) as exc:
        raise OSError(
            f"could not load the Qwen3-VL {what} from vlm_path={vlm_path!r}: {exc}\n"
            "Set --policy.vlm_path to a local folder holding a saved Qwen3-VL (model, tokenizer and processor, "
            "e.g. a download of Qwen/Qwen3-VL-2B-Instruct), make the Hugging Face Hub reachable, or, for a smoke "
            "run, create a tiny random one with `activearena-make-tiny-vlm DIR`."
        ) from exc


def load_policy_vlm(vlm_path: str, dtype=None, attn_implementation: str = "sdpa"):
    """The Qwen3-VL as every ActiveArena-VLA policy builds it: loaded from ``vlm_path`` (float32 unless
    ``dtype``), the patch embedding as one linear layer, the vision attention batched over images.
    The vision cache builds its tower the same way, so the two compute the same features."""
    import torch
    from transformers import Qwen3VLForConditionalGeneration

    from .patch_embedding import patch_embed_as_linear
    from .vision_attention import batch_vision_attention

    vlm = load_from_vlm_path(
        Qwen3VLForConditionalGeneration.from_pretrained,
        vlm_path,
        "model",
        dtype=dtype or torch.float32,
        attn_implementation=attn_implementation,
    )
    patch_embed_as_linear(vlm)
    batch_vision_attention(vlm)
    return vlm
