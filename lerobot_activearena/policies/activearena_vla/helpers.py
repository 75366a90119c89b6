"""Public helpers the ActiveArena-VLA heads share: precision, which chunk steps are real, and how stored
frames become the backbone's left-padded frame slots."""

from __future__ import annotations

import functools
import warnings

import torch
from torch import Tensor

from .configuration_activearena_vla import ActiveArenaVLAConfig


def weights_dtype(config: ActiveArenaVLAConfig) -> torch.dtype:
    """The backbone's parameter dtype: float32 master weights unless ``weights_dtype=bfloat16``."""
    if config.weights_dtype == "bfloat16":
        warnings.warn(
            "weights_dtype=bfloat16: the backbone's parameters are bfloat16, so AdamW updates smaller "
            "than their last bit (most of them at lr 1e-5) round away. Keep the default float32 master "
            "weights (bfloat16 compute comes from dtype=auto/bfloat16) unless memory forces this.",
            UserWarning,
            stacklevel=3,
        )
        return torch.bfloat16
    return torch.float32


# What a selectively checkpointed block keeps: the outputs of its matrix multiplies and attention (the
# compute); its norms, activations, rotary embeddings and casts are recomputed from them.
SAVED_OPS = (
    "mm",
    "addmm",
    "bmm",
    "baddbmm",
    "_scaled_dot_product_flash_attention",
    "_scaled_dot_product_efficient_attention",
    "_scaled_dot_product_cudnn_attention",
    "_scaled_dot_product_flash_attention_for_cpu",
)


def _keep_compute(ctx, op, *args, **kwargs):
    from torch.utils.checkpoint import CheckpointPolicy

    name = op.overloadpacket.__name__ if hasattr(op, "overloadpacket") else ""
    return CheckpointPolicy.MUST_SAVE if name in SAVED_OPS else CheckpointPolicy.PREFER_RECOMPUTE


def checkpoint_layers(vlm, layers: str, mode: str = "full", language_layers: int | None = None) -> None:
    """Gradient checkpointing of Qwen3-VL's ``layers`` (all | vision | language), of the language
    model only its first ``language_layers`` decoder layers when given. ``mode`` full: those blocks
    keep only their inputs and recompute the rest in the backward pass; selective: they also keep the
    outputs of their matrix multiplies and attention (``SAVED_OPS``) and recompute only the cheap
    element-wise work (PyTorch's selective activation checkpointing)."""
    kwargs = {"use_reentrant": False}
    if mode == "selective":
        from torch.utils.checkpoint import create_selective_checkpoint_contexts

        kwargs["context_fn"] = functools.partial(create_selective_checkpoint_contexts, _keep_compute)
    elif mode != "full":
        raise ValueError(f"checkpointing mode must be 'full' or 'selective', got {mode!r}")
    vlm.gradient_checkpointing_enable(gradient_checkpointing_kwargs=kwargs)
    decoder = vlm.model.language_model.layers
    if language_layers is not None and language_layers > len(decoder):
        raise ValueError(
            f"gradient_checkpointing_language_layers={language_layers}, but the language model has "
            f"{len(decoder)} decoder layers"
        )
    if layers != "all":
        part = {"vision": vlm.model.visual, "language": vlm.model.language_model}[layers]
        inside = {id(m) for m in part.modules()}
        for module in vlm.modules():
            if hasattr(module, "gradient_checkpointing") and id(module) not in inside:
                module.gradient_checkpointing = False
    if language_layers is not None and layers != "vision":
        for i, layer in enumerate(decoder):
            layer.gradient_checkpointing = i < language_layers


def compile_layers(vlm, layers: str) -> None:
    """``torch.compile`` Qwen3-VL's vision blocks and/or decoder layers in place (``Module.compile``:
    the same modules and state dict), each with dynamic shapes so that the batches' varying image
    and token counts reuse one graph. Gradient checkpointing stays outside the compiled blocks."""
    parts = {"vision": [vlm.model.visual.blocks], "language": [vlm.model.language_model.layers]}
    parts["all"] = parts["vision"] + parts["language"]
    if layers == "none":
        return
    if layers not in parts:
        raise ValueError(f"compile_layers must be none, all, vision or language, got {layers!r}")
    for blocks in parts[layers]:
        for block in blocks:
            block.compile(dynamic=True)


def residual_in_compute_dtype(vlm) -> None:
    """Under autocast, start the vision tower's and the language model's residual streams in the
    compute dtype (bfloat16) instead of float32 (the embeddings' dtype): their additions, norms'
    inputs and blocks' kept inputs are then half the bytes, as when the model's weights are bfloat16."""

    def to_compute_dtype(t: Tensor) -> Tensor:
        device = t.device.type
        if t.is_floating_point() and torch.is_autocast_enabled(device):
            return t.to(torch.get_autocast_dtype(device))
        return t

    def vision(_module, args, kwargs):
        return (to_compute_dtype(args[0]), *args[1:]), kwargs

    def language(_module, args, kwargs):
        if kwargs.get("inputs_embeds") is not None:
            kwargs["inputs_embeds"] = to_compute_dtype(kwargs["inputs_embeds"])
        return args, kwargs

    vlm.model.visual.blocks[0].register_forward_pre_hook(vision, with_kwargs=True)
    vlm.model.language_model.register_forward_pre_hook(language, with_kwargs=True)


def in_precision(method):
    """Run a policy ``method`` under the policy's autocast (bfloat16 compute over float32 weights when
    ``config.autocast_bfloat16``)."""

    @functools.wraps(method)
    def wrapper(self, *args, **kwargs):
        with torch.autocast(
            device_type=self.device.type,
            dtype=torch.bfloat16,
            enabled=self.config.autocast_bfloat16,
        ):
            return method(self, *args, **kwargs)

    return wrapper


def real_steps(batch: dict[str, Tensor], target: Tensor) -> Tensor:
    """(B, chunk) True where the chunk's step is real (LeRobot pads past an episode's end)."""
    if "action_is_pad" in batch:
        return ~batch["action_is_pad"]
    return torch.ones(target.shape[:2], dtype=torch.bool, device=target.device)


def blank_entry(entry: dict) -> dict:
    """A memory entry's blanked twin for ``memory_ablation=blank``: the same slot, grid and state, its
    image uniform gray (zeros after the processor's 0.5 mean / std), its vision features computed
    from that gray image once and kept on the entry."""
    if "blank" not in entry:
        entry["blank"] = dict(entry, pixels=torch.zeros_like(entry["pixels"]), vision=None)
    return entry["blank"]


def blank_memory_pixels(pixels: Tensor, valid: Tensor, grid: Tensor) -> Tensor:
    """``blank_entry`` for a dataset batch: the pixel values (every present frame's, packed in
    (sample, slot) order; ``grid`` (batch, slots, 3)) of every frame before a sample's last slot (its
    memory frames) set to gray (zeros); the current frames' kept."""
    valid = valid.cpu()
    slots = valid.nonzero()[:, 1]
    try:
        rows = frame_rows(pixels, grid.cpu()[valid])
    except ValueError as err:
        raise ValueError(
            f"the batch's pixel values do not fit the {len(slots)} frames frame_valid marks ({err}): blanking "
            "needs every present frame's (a batch read through a vision cache has only the current frame's)"
        ) from err
    last = valid.shape[1] - 1
    return pack_frames(
        [r if s == last else torch.zeros_like(r) for r, s in zip(rows, slots.tolist(), strict=True)]
    )


def drop_memory_frames(pixels: Tensor, valid: Tensor, grid: Tensor) -> tuple[Tensor, Tensor]:
    """``memory_ablation=drop`` for a dataset batch: the pixel values of the current frames only and
    ``valid`` with every memory slot absent, as at an episode's first frame."""
    kept, kept_valid, _ = drop_sample_memory(
        pixels, grid, valid, None, torch.ones(len(valid), dtype=torch.bool)
    )
    return kept, kept_valid


def drop_sample_memory(
    pixels: Tensor, grid: Tensor, valid: Tensor, cache: dict | None, dropped: Tensor
) -> tuple[Tensor, Tensor, dict | None]:
    """``memory_dropout`` for a training batch: the memory slots of the samples ``dropped`` (B,) marks
    made absent, as at an episode's first frame. Returns the pixel values without those frames' rows,
    ``valid`` without their slots and the vision cache ((sample, slot) -> entry: frames whose features
    come from the cache carry no pixels) without their entries."""
    valid_cpu = valid.cpu()
    gone = valid_cpu & dropped.cpu()[:, None]
    gone[:, -1] = False
    if not gone.any():
        return pixels, valid, cache
    cached = set(cache or {})
    carried = [(b, s) for b, s in valid_cpu.nonzero().tolist() if (b, s) not in cached]
    try:
        rows = frame_rows(pixels, grid.cpu()[[b for b, _ in carried], [s for _, s in carried]])
    except ValueError as err:
        raise ValueError(
            f"the batch's pixel values do not fit the {len(carried)} frames frame_valid marks outside the "
            f"vision cache ({err}): a batch read through a vision cache has only the current frame's, "
            "whose memory frames are left out through the cache"
        ) from err
    kept = pack_frames([r for r, (b, s) in zip(rows, carried, strict=True) if not gone[b, s]])
    if cache is not None:
        cache = {k: e for k, e in cache.items() if not gone[k]}
    return kept, (valid_cpu & ~gone).to(valid.device), cache


def frame_rows(pixels: Tensor, grid: Tensor) -> list[Tensor]:
    """``pixels`` (either PIXELS layout) as one (patches, dim) tensor per frame of the (frames, 3) grid."""
    rows = list(pixels) if pixels.dim() == 3 else list(torch.split(pixels, grid.prod(-1).tolist()))
    if len(rows) != len(grid) or any(len(r) != int(g.prod()) for r, g in zip(rows, grid, strict=False)):
        raise ValueError(
            f"pixel values of {sum(len(r) for r in rows)} patches do not fit the grids {grid.tolist()}"
        )
    return rows


def pack_frames(rows: list[Tensor]) -> Tensor:
    """Per-frame (patches, dim) pixel values in PIXELS' layout: stacked where all have one size."""
    if len({tuple(r.shape) for r in rows}) == 1:
        return torch.stack(rows)
    return torch.cat(rows)


def stack_frames(entries: list[list[dict]], slots: int, with_state: bool = True):
    """Per sample, its stored frames (dicts with ``pixels``, ``grid``, ``state``; oldest first, the
    last one the current frame) in the last of ``slots`` left-padded slots. Returns ``pixels`` (the
    stored frames' only, packed in (sample, slot) order), ``grid``,
    ``valid``, ``state`` (None without states) and the vision cache (sample, slot) -> entry, through which
    the backbone reuses an entry's ``vision`` features or stores them there."""
    first = entries[0][-1]
    batch_size = len(entries)
    pixels = pack_frames([e["pixels"] for row in entries for e in row])
    grid = first["grid"].new_ones((batch_size, slots, 3))
    valid = torch.zeros(batch_size, slots, dtype=torch.bool)
    state = None
    if with_state and first["state"] is not None:
        state = first["state"].new_zeros((batch_size, slots, first["state"].shape[-1]))
    cache = {}
    for b, row in enumerate(entries):
        for slot, e in zip(range(slots - len(row), slots), row, strict=True):
            grid[b, slot], valid[b, slot] = e["grid"], True
            if state is not None:
                state[b, slot] = e["state"]
            cache[(b, slot)] = e
    return pixels, grid, valid, state, cache
