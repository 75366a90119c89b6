"""A tiny random Qwen3-VL with its own tokenizer and image processor, saved like a Hub checkpoint.

No weights can be downloaded here, so tests and smoke runs load this through exactly the code path
that loads ``Qwen/Qwen3-VL-2B-Instruct`` (``from_pretrained(path)``). The tokenizer is a byte-level
BPE trained with ``tokenizers`` on the benchmark's instructions, with Qwen's chat and vision tokens.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from ...sim.scene import HEAD_HEIGHT, HEAD_WIDTH

CHAT_TEMPLATE = (
    "{% for m in messages %}<|im_start|>{{ m['role'] }}\n"
    "{% if m['content'] is string %}{{ m['content'] }}{% else %}{% for c in m['content'] %}"
    "{% if c['type'] == 'image' %}<|vision_start|><|image_pad|><|vision_end|>{% else %}{{ c['text'] }}{% endif %}"
    "{% endfor %}{% endif %}<|im_end|>\n{% endfor %}{% if add_generation_prompt %}<|im_start|>assistant\n{% endif %}"
)
SPECIAL_TOKENS = [
    "<|endoftext|>",
    "<|im_start|>",
    "<|im_end|>",
    "<|vision_start|>",
    "<|vision_end|>",
    "<|image_pad|>",
    "<|video_pad|>",
    "<think>",
    "</think>",
]


def _corpus(texts: Sequence[str]) -> list[str]:
    lines = [
        "Frames: total history current. Now the subtask is",
        "The images are ordered from earliest to latest.",
        *texts,
    ]
    return lines * 4


# Qwen/Qwen3-VL-2B-Instruct's dimensions (text: the Qwen3-1.7B decoder; vision: 24-layer ViT with
# DeepStack taps 5/11/17), for measuring memory and latency at the real size without its weights.
QWEN3_VL_2B = {
    "text": {
        "vocab_size": 151936,
        "hidden_size": 2048,
        "intermediate_size": 6144,
        "num_hidden_layers": 28,
        "num_attention_heads": 16,
        "num_key_value_heads": 8,
        "head_dim": 128,
        "max_position_embeddings": 262144,
        "rope_parameters": {
            "rope_type": "default",
            "rope_theta": 5000000.0,
            "mrope_section": [24, 20, 20],
            "mrope_interleaved": True,
        },
    },
    "vision": {
        "depth": 24,
        "hidden_size": 1024,
        "intermediate_size": 4096,
        "num_heads": 16,
        "out_hidden_size": 2048,
        "num_position_embeddings": 2304,
        "deepstack_visual_indexes": [5, 11, 17],
    },
}


def qwen3_vl_config(text: dict, vision: dict, ids: dict[str, int] | None = None, patch: int = 16):
    """A Qwen3-VL config from text / vision dimensions (``patch`` px patches, 2x2 merge, tied
    embeddings) and, when given, the tokenizer's special-token ids."""
    from transformers import Qwen3VLConfig

    tokens = {}
    if ids is not None:
        tokens = {
            "image_token_id": ids["<|image_pad|>"],
            "video_token_id": ids["<|video_pad|>"],
            "vision_start_token_id": ids["<|vision_start|>"],
            "vision_end_token_id": ids["<|vision_end|>"],
        }
        text = dict(text, pad_token_id=ids["<|endoftext|>"])
    return Qwen3VLConfig(
        text_config=dict(text, tie_word_embeddings=True),
        vision_config=dict(vision, patch_size=patch, spatial_merge_size=2, temporal_patch_size=2),
        tie_word_embeddings=True,
        **tokens,
    )


def make_tiny_vlm(
    out_dir: str | Path,
    hidden: int = 64,
    layers: int = 2,
    vocab: int = 1024,
    seed: int = 0,
    architecture: str = "tiny",
    texts: Sequence[str] = (),
    patch: int = 16,
    vision_hidden: int | None = None,
    vision_depth: int = 2,
) -> Path:
    """Write a random Qwen3-VL, tokenizer and processor to ``out_dir``: tiny (``hidden`` / ``layers``), or
    with ``architecture="qwen3-vl-2b"`` the real 2B model's dimensions (saved in bfloat16, ~4.3 GB).
    ``texts`` (e.g. the benchmark's instructions and subtasks) join the tiny tokenizer's corpus.
    ``patch`` (tiny only): the vision patch side in pixels; 32 reads a 192 x 256 image as the same 12
    tokens that 16 px patches make of 96 x 128, with every pixel in the patch embedding.
    ``vision_hidden`` / ``vision_depth`` (tiny only): the vision tower's width (default ``hidden``) and
    blocks; its merger still projects to ``hidden``."""
    if architecture not in ("tiny", "qwen3-vl-2b"):
        raise ValueError(f"architecture must be 'tiny' or 'qwen3-vl-2b', got {architecture!r}")
    if architecture != "tiny" and patch != 16:
        raise ValueError(f"the 2B architecture has 16 px patches; got patch={patch}")
    vision_hidden = hidden if vision_hidden is None else vision_hidden
    if architecture != "tiny" and (vision_hidden != hidden or vision_depth != 2):
        raise ValueError("vision_hidden / vision_depth apply to the tiny architecture only")
    if vision_depth < 2 or vision_hidden < 32 or vision_hidden % 4:
        raise ValueError(
            f"the vision tower needs depth >= 2 and a width that is a multiple of 4 and >= 32; "
            f"got depth {vision_depth}, width {vision_hidden}"
        )
    import torch
    from tokenizers import Tokenizer, decoders, models, pre_tokenizers, trainers
    from transformers import (
        Qwen2TokenizerFast,
        Qwen2VLImageProcessor,
        Qwen3VLForConditionalGeneration,
        Qwen3VLProcessor,
    )
    from transformers.models.qwen3_vl.video_processing_qwen3_vl import Qwen3VLVideoProcessor

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    bpe = Tokenizer(models.BPE())
    bpe.pre_tokenizer = pre_tokenizers.ByteLevel(add_prefix_space=False)
    bpe.decoder = decoders.ByteLevel()
    trainer = trainers.BpeTrainer(
        vocab_size=vocab - len(SPECIAL_TOKENS),
        special_tokens=SPECIAL_TOKENS,
        initial_alphabet=pre_tokenizers.ByteLevel.alphabet(),
        show_progress=False,
    )
    bpe.train_from_iterator(_corpus(texts), trainer)
    tok = Qwen2TokenizerFast(
        tokenizer_object=bpe,
        eos_token="<|im_end|>",
        pad_token="<|endoftext|>",
        unk_token=None,
        bos_token=None,
    )
    tok.chat_template = CHAT_TEMPLATE
    ids = {t: tok.convert_tokens_to_ids(t) for t in SPECIAL_TOKENS}
    image_proc = Qwen2VLImageProcessor(
        patch_size=patch,
        merge_size=2,
        temporal_patch_size=2,
        image_mean=[0.5] * 3,
        image_std=[0.5] * 3,
        min_pixels=patch * patch * 4,
        max_pixels=HEAD_WIDTH * HEAD_HEIGHT,
    )
    video_proc = Qwen3VLVideoProcessor(patch_size=patch, merge_size=2, temporal_patch_size=2)
    processor = Qwen3VLProcessor(
        image_processor=image_proc, tokenizer=tok, video_processor=video_proc, chat_template=CHAT_TEMPLATE
    )
    heads = 4
    text = {
        "vocab_size": len(tok),
        "hidden_size": hidden,
        "intermediate_size": 2 * hidden,
        "num_hidden_layers": layers,
        "num_attention_heads": heads,
        "num_key_value_heads": 2,
        "head_dim": hidden // heads,
        "max_position_embeddings": 8192,
        "rope_parameters": {
            "rope_type": "default",
            "rope_theta": 10000.0,
            "mrope_section": [2, 3, 3],
            "mrope_interleaved": True,
        },
    }
    vision = {
        "depth": vision_depth,
        "hidden_size": vision_hidden,
        "intermediate_size": 2 * vision_hidden,
        "num_heads": heads,
        "out_hidden_size": hidden,
        "num_position_embeddings": 1024,
        "deepstack_visual_indexes": [1],
    }
    if architecture == "qwen3-vl-2b":
        text, vision = dict(QWEN3_VL_2B["text"]), dict(QWEN3_VL_2B["vision"])
    config = qwen3_vl_config(text, vision, ids, patch=patch)
    torch.manual_seed(seed)
    model = Qwen3VLForConditionalGeneration(config)
    if architecture != "tiny":
        model = model.to(torch.bfloat16)
    model.save_pretrained(out)
    processor.save_pretrained(out)
    return out
