"""Memory of one ActiveArena-VLA training step at Qwen3-VL-2B's shapes, counted on the CPU.

    python benchmarks/activation_memory.py                 # the usual batch (batch 7, K = 12)
    python benchmarks/activation_memory.py --all-valid     # every history frame present (91 images)
    python benchmarks/activation_memory.py --compile-layers all   # what compiled blocks keep instead

Runs one forward pass of the OFT policy on a random Qwen3-VL with the 2B model's widths, cut to
``--vision-depth`` vision blocks and ``--text-layers`` language layers, under bfloat16 autocast, and
counts the bytes autograd keeps for the backward pass (``torch.autograd.graph.saved_tensors_hooks``;
each storage once, parameters left out) per vision block, per language layer and for the rest. Scaled
to the full depth (24 blocks, 28 layers) and added to the float32 weights, gradients and AdamW moments
of all 2.2 B parameters, this predicts a GPU's peak for each gradient-checkpointing choice: a
checkpointed block keeps only its input and recomputes the rest, one block at a time, in the backward
pass. The saved bytes are listed by dtype and by the operator that saved them, which shows what a
change in precision or in the norms would save. With ``--compile-layers`` the blocks run compiled
(inductor on the CPU): its partitioner recomputes cheap element-wise results in the backward pass
instead of keeping them, so they keep less. ``oft_train_step.py --sweep`` measures the same on a GPU.
"""

from __future__ import annotations

import argparse
import contextlib
import tempfile
from collections import defaultdict
from pathlib import Path

import torch

GIB = 2**30


class SavedBytes:
    """Counts autograd's saved tensors by region (the innermost tracked module), dtype and operator."""

    def __init__(self, model: torch.nn.Module, regions: dict[str, list[torch.nn.Module]]):
        self.params = {p.untyped_storage().data_ptr() for p in model.parameters()}
        self.seen: set[int] = set()
        self.stack = ["rest"]
        self.by_region: dict[str, int] = defaultdict(int)
        self.by_kind: dict[tuple[str, str, str], int] = defaultdict(int)
        self.inputs: dict[str, int] = defaultdict(int)
        self.selective: dict[str, int] = defaultdict(int)
        self.handles = []
        for name, modules in regions.items():
            for m in modules:
                self.handles.append(m.register_forward_pre_hook(self._enter(name)))
                self.handles.append(m.register_forward_hook(self._leave))

    def _enter(self, name: str):
        def hook(_module, args):
            self.stack.append(name)
            self.inputs[name] += args[0].numel() * args[0].element_size()

        return hook

    def _leave(self, *_):
        self.stack.pop()

    def pack(self, t: torch.Tensor) -> torch.Tensor:
        storage = t.untyped_storage()
        ptr = storage.data_ptr()
        if ptr not in self.params and ptr not in self.seen:
            self.seen.add(ptr)
            op = t.grad_fn.name() if t.grad_fn is not None else "leaf/input"
            self.by_region[self.stack[-1]] += storage.nbytes()
            self.by_kind[(self.stack[-1], str(t.dtype).removeprefix("torch."), op)] += storage.nbytes()
        return t

    def kept_by_selective(self):
        """A dispatch mode that adds up the outputs of the ops selective checkpointing keeps."""
        from torch.utils._python_dispatch import TorchDispatchMode

        from lerobot_activearena.policies.activearena_vla.helpers import SAVED_OPS

        counter = self

        class KeptOutputs(TorchDispatchMode):
            def __torch_dispatch__(self, func, types, args=(), kwargs=None):
                out = func(*args, **(kwargs or {}))
                if func.overloadpacket.__name__ in SAVED_OPS:
                    for t in out if isinstance(out, tuple) else (out,):
                        if isinstance(t, torch.Tensor):
                            counter.selective[counter.stack[-1]] += t.numel() * t.element_size()
                return out

        return KeptOutputs()

    def close(self) -> None:
        for h in self.handles:
            h.remove()


def write_cut_2b(out: Path, vision_depth: int, text_layers: int) -> Path:
    """A random Qwen3-VL with the 2B model's widths and ``vision_depth`` / ``text_layers`` blocks (the
    DeepStack taps on the first three vision blocks), with the tiny model's tokenizer and processor."""
    from transformers import AutoTokenizer, Qwen3VLForConditionalGeneration

    from lerobot_activearena.policies.activearena_vla.tiny_vlm import (
        QWEN3_VL_2B,
        SPECIAL_TOKENS,
        make_tiny_vlm,
        qwen3_vl_config,
    )

    if vision_depth < 3:
        raise SystemExit("--vision-depth must be >= 3 (the 2B model's three DeepStack taps)")
    make_tiny_vlm(out)
    tok = AutoTokenizer.from_pretrained(out)
    ids = {t: tok.convert_tokens_to_ids(t) for t in SPECIAL_TOKENS}
    text = dict(QWEN3_VL_2B["text"], num_hidden_layers=text_layers)
    vision = dict(QWEN3_VL_2B["vision"], depth=vision_depth, deepstack_visual_indexes=[0, 1, 2])
    Qwen3VLForConditionalGeneration(qwen3_vl_config(text, vision, ids)).save_pretrained(out)
    return out


def full_2b_parameters() -> int:
    """Parameters of the whole 2B backbone (built on the meta device: no memory)."""
    from transformers import Qwen3VLForConditionalGeneration

    from lerobot_activearena.policies.activearena_vla.tiny_vlm import QWEN3_VL_2B, qwen3_vl_config

    with torch.device("meta"):
        model = Qwen3VLForConditionalGeneration(qwen3_vl_config(QWEN3_VL_2B["text"], QWEN3_VL_2B["vision"]))
    return sum(p.numel() for p in model.parameters())


def main() -> None:
    from oft_train_step import add_memory_options, synthetic_setup

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--batch-size", type=int, default=7)
    p.add_argument("--history", type=int, default=12)
    p.add_argument("--all-valid", action="store_true", help="every history frame present")
    p.add_argument("--episode-frames", type=int, default=166)
    p.add_argument("--vision-depth", type=int, default=3)
    p.add_argument("--text-layers", type=int, default=2)
    add_memory_options(p)
    p.add_argument(
        "--padding-batches", type=int, default=50, help="batches over which the mean padding share is taken"
    )
    p.add_argument("--top", type=int, default=12, help="rows of the by-operator table")
    p.add_argument(
        "--budget-gib",
        type=float,
        default=70.0,
        help="the peak to fit: how many language layers to checkpoint beside the vision tower",
    )
    args = p.parse_args()
    if args.padding_batches < 1:
        p.error("--padding-batches must be >= 1")

    from lerobot_activearena.policies.activearena_oft.configuration_activearena_oft import (
        ActiveArenaOFTConfig,
    )
    from lerobot_activearena.policies.activearena_vla.tiny_vlm import QWEN3_VL_2B

    torch.manual_seed(0)
    tmp = tempfile.TemporaryDirectory(prefix="aa_act_mem_")  # the cut model: ~2 GB, removed at exit
    vlm = write_cut_2b(Path(tmp.name), args.vision_depth, args.text_layers)
    cfg = ActiveArenaOFTConfig(
        vlm_path=str(vlm),
        device="cpu",
        history=args.history,
        dtype="bfloat16",
        unpad_language_model=args.unpad_language_model,
        residual_dtype=args.residual_dtype,
        compile_layers=args.compile_layers,
    )
    cfg.think = "instruction"  # synthetic batches have no subtask annotations: a span of similar length
    policy, pre, batches = synthetic_setup(cfg, args.batch_size, args.episode_frames, args.all_valid)
    policy.train()
    model = policy.vlm.model
    blocks, layers = list(model.visual.blocks), list(model.language_model.layers)
    counter = SavedBytes(policy, {"vision block": blocks, "language layer": layers})
    assemble, shapes = policy.assemble, []

    def assemble_and_record(*a, **k):
        seq = assemble(*a, **k)
        shapes.append((seq["kind"].numel(), int((seq["kind"] >= 0).sum())))
        return seq

    policy.assemble = assemble_and_record
    batch = pre(next(batches))
    images = int(batch["observation.vlm.frame_valid"].sum())
    compiled = args.compile_layers != "none"
    # selective checkpointing does not combine with compiled blocks (and its counter would trace into them)
    selective = contextlib.nullcontext() if compiled else counter.kept_by_selective()
    with torch.autograd.graph.saved_tensors_hooks(counter.pack, lambda t: t), selective:
        loss, _ = policy.forward(batch)
    counter.close()
    del loss
    with torch.no_grad():  # the padding share over more batches (sequences assembled, no forward pass)
        for _ in range(args.padding_batches):
            policy.assemble(*policy.training_args(pre(next(batches))))
    mean_padding = 1 - sum(r for _, r in shapes[1:]) / sum(n for n, _ in shapes[1:])

    depth, n_layers = QWEN3_VL_2B["vision"]["depth"], QWEN3_VL_2B["text"]["num_hidden_layers"]
    per_block = counter.by_region["vision block"] / len(blocks)
    per_layer = counter.by_region["language layer"] / len(layers)
    in_block = counter.inputs["vision block"] / len(blocks)
    in_layer = counter.inputs["language layer"] / len(layers)
    rest = counter.by_region["rest"]
    sel_block = in_block + counter.selective["vision block"] / len(blocks)
    sel_layer = in_layer + counter.selective["language layer"] / len(layers)
    n_params = full_2b_parameters() + sum(
        p.numel() for n, p in policy.named_parameters() if not n.startswith("vlm.")
    )
    static = 16 * n_params  # float32 weights + gradients + two AdamW moments

    print(
        f"batch {args.batch_size}, K = {args.history}, {'all-valid' if args.all_valid else 'usual'} batch: "
        f"{images} images; bfloat16 autocast over float32 weights (the presets' precision), residual streams "
        f"{args.residual_dtype}" + (f"; compiled layers: {args.compile_layers}" if compiled else "")
    )
    padded, real = shapes[0]
    print(
        f"language model: {real} real tokens in {padded} positions of the padded batch ({1 - real / padded:.0%} "
        f"padding; {mean_padding:.0%} over the next {args.padding_batches} batches); "
        + (
            "run once per sample: pads not computed"
            if args.unpad_language_model
            else "all positions computed"
        )
    )
    print(
        f"weights + gradients + AdamW moments ({n_params / 1e9:.2f} B parameters, float32): {static / GIB:.1f} GiB"
    )
    print(
        f"saved for backward: {per_block / GIB:.3f} GiB per vision block (input {in_block / GIB:.3f}), "
        f"{per_layer / GIB:.3f} GiB per language layer (input {in_layer / GIB:.3f}), {rest / GIB:.2f} GiB the rest"
        + (
            ""
            if compiled
            else f"; selective checkpointing keeps {sel_block / GIB:.3f} GiB per vision block, "
            f"{sel_layer / GIB:.3f} per language layer (input + matmul and attention outputs)"
        )
    )
    print("predicted peak (static + saved; a checkpointed block keeps its input, one recomputes at a time):")
    for name, keep_block, keep_layer in (
        ("all", in_block, in_layer),
        ("vision", in_block, per_layer),
        ("language", per_block, in_layer),
        ("none", per_block, per_layer),
        ("all, selective", sel_block, sel_layer),
        ("vision, selective", sel_block, per_layer),
    ):
        if compiled and "selective" in name:
            continue
        vision, text = depth * keep_block, n_layers * keep_layer
        recompute = max(per_block - keep_block, per_layer - keep_layer)
        total = static + vision + text + rest + recompute
        print(
            f"  checkpointing {name:>17}: {total / GIB:6.1f} GiB (vision {vision / GIB:5.1f}, language "
            f"{text / GIB:5.1f}, rest {rest / GIB:4.1f}, recompute {recompute / GIB:4.1f})"
        )

    # vision tower + the first n decoder layers (gradient_checkpointing_language_layers=n)
    def partial_peak(n: int) -> float:
        recompute = per_block - in_block if n == 0 else max(per_block - in_block, per_layer - in_layer)
        return static + depth * in_block + n * in_layer + (n_layers - n) * per_layer + rest + recompute

    fits = [n for n in range(n_layers + 1) if partial_peak(n) <= args.budget_gib * GIB]
    if fits:
        n = fits[0]
        print(
            f"to fit {args.budget_gib:g} GiB: the vision tower and the first {n} of {n_layers} language layers "
            f"(gradient_checkpointing_language_layers={n}): {partial_peak(n) / GIB:.1f} GiB; each further "
            f"layer saves {(per_layer - in_layer) / GIB:.2f} GiB"
        )
    else:
        print(
            f"no checkpointing choice fits {args.budget_gib:g} GiB (all layers: {partial_peak(n_layers) / GIB:.1f})"
        )
    print(f"saved bytes by region, dtype and the operator that made them (top {args.top}):")
    scale = {"vision block": depth / len(blocks), "language layer": n_layers / len(layers), "rest": 1}
    rows = sorted(((k, v * scale[k[0]]) for k, v in counter.by_kind.items()), key=lambda kv: -kv[1])
    for (region, dtype, op), nbytes in rows[: args.top]:
        print(f"  {region:>14} {dtype:>8} made by {op:<28} {nbytes / GIB:6.2f} GiB at full depth")


if __name__ == "__main__":
    main()
