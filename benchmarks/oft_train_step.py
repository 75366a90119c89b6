"""ActiveArena-VLA training-step time, peak memory and inference latency per chunk, for each head.

    python benchmarks/oft_train_step.py                      # tiny random Qwen3-VL on the CPU
    python benchmarks/oft_train_step.py --policy-type activearena_groot   # the DiT head instead
    python benchmarks/oft_train_step.py --policy-type activearena_fast    # FAST action tokens
    python benchmarks/oft_train_step.py --policy-type activearena_plan    # Plan: executor (+ planner)
    python benchmarks/oft_train_step.py --policy-type activearena_planner # Plan: the planner's training
    python benchmarks/oft_train_step.py --synthetic          # no dataset: random batches shaped like it
    python benchmarks/oft_train_step.py --vlm-path Qwen/Qwen3-VL-2B-Instruct --device cuda --batch-size 7
    activearena-make-tiny-vlm /tmp/qwen3vl_2b_random --architecture qwen3-vl-2b   # 2B dimensions, random
    python benchmarks/oft_train_step.py --vlm-path /tmp/qwen3vl_2b_random --steps 0 --weights-dtype bfloat16 --skip-uncached --decode-tokens 8   # CPU inference

Builds a small ActiveArena dataset (or uses --root), runs the real LeRobot factories
(make_policy, make_pre_post_processors, the dataset with the config's delta_timestamps), and times
preprocess + forward + backward + AdamW step at the given batch size with K history frames, then
``select_action`` latency at a chunk boundary (one chunk = one VLM forward) and, with think=subtask,
the greedy ``<think>`` decoding that memory=subtask adds per chunk (KV-cached vs re-encoding). Peak memory is
``torch.cuda.max_memory_allocated`` on CUDA and the process's peak RSS on the CPU.
"""

from __future__ import annotations

import argparse
import os
import resource
import tempfile
import time
import traceback
from collections import Counter
from pathlib import Path

import torch
from lerobot.datasets.dataset_metadata import LeRobotDatasetMetadata
from lerobot.datasets.factory import resolve_delta_timestamps
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.policies.factory import make_policy, make_pre_post_processors
from torch.utils._python_dispatch import TorchDispatchMode

from lerobot_activearena.datasets_build.pipeline import build_dataset
from lerobot_activearena.datasets_build.plan import BuildPlan
from lerobot_activearena.policies.activearena_fast import ActiveArenaFASTConfig
from lerobot_activearena.policies.activearena_groot import ActiveArenaGR00TConfig
from lerobot_activearena.policies.activearena_oft.configuration_activearena_oft import ActiveArenaOFTConfig
from lerobot_activearena.policies.activearena_plan import ActiveArenaPlanConfig
from lerobot_activearena.policies.activearena_planner import ActiveArenaPlannerConfig
from lerobot_activearena.policies.activearena_vla.tiny_vlm import make_tiny_vlm

CONFIGS = {
    "activearena_oft": ActiveArenaOFTConfig,
    "activearena_groot": ActiveArenaGR00TConfig,
    "activearena_fast": ActiveArenaFASTConfig,
    "activearena_planner": ActiveArenaPlannerConfig,
    "activearena_plan": ActiveArenaPlanConfig,
}


def peak_memory(cuda: bool) -> str:
    if cuda:
        return f"{torch.cuda.max_memory_allocated() / 2**30:.2f} GiB GPU (max_memory_allocated)"
    return f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20:.2f} GiB peak RSS"


def make_optimizer(policy, fused: bool) -> torch.optim.AdamW:
    """The paper's AdamW (the presets' betas, eps and weight decay); ``fused``: torch's fused kernel."""
    extra = {"fused": True} if fused else {}
    return torch.optim.AdamW(
        policy.get_optim_params(), betas=(0.9, 0.95), eps=1e-8, weight_decay=1e-8, **extra
    )


def train_step(policy, pre, opt, raw: dict, cuda: bool) -> tuple[float, float, dict]:
    """One preprocess + forward + backward + AdamW step; returns its preprocessing and total seconds
    (synchronised on CUDA) and the preprocessed batch."""
    if cuda:
        torch.cuda.synchronize()
    t0 = time.perf_counter()
    batch = pre(raw)
    if cuda:
        torch.cuda.synchronize()
    t1 = time.perf_counter()
    loss, _ = policy.forward(batch)
    opt.zero_grad(set_to_none=True)
    loss.backward()
    torch.nn.utils.clip_grad_norm_(policy.parameters(), 1.0)
    opt.step()
    if cuda:
        torch.cuda.synchronize()
    return t1 - t0, time.perf_counter() - t0, batch


class OperatorCount(TorchDispatchMode):
    """Counts the ATen operators dispatched while it is active, by name, and where the host syncs
    (``aten._local_scalar_dense``) come from: the innermost caller outside torch."""

    def __init__(self, cpu: bool):
        super().__init__()
        self.cpu = cpu  # on a CPU run every read is listed; on a GPU only reads of device tensors
        self.calls: Counter = Counter()
        self.sync_sites: Counter = Counter()

    def __torch_dispatch__(self, func, types, args=(), kwargs=None):
        self.calls[str(func)] += 1
        if func is torch.ops.aten._local_scalar_dense.default and (self.cpu or args[0].device.type != "cpu"):
            for frame in reversed(traceback.extract_stack()[:-1]):
                if f"{os.sep}torch{os.sep}" not in frame.filename:
                    where = frame.filename.split("site-packages" + os.sep)[-1].split(
                        "lerobot_activearena" + os.sep
                    )[-1]
                    self.sync_sites[f"{where}:{frame.lineno} ({frame.line})"] += 1
                    break
        return func(*args, **(kwargs or {}))


def add_memory_options(p: argparse.ArgumentParser) -> None:
    """The policy options that change a training step's memory, shared with activation_memory.py."""
    p.add_argument(
        "--residual-dtype",
        choices=["float32", "compute"],
        default="float32",
        help="the backbone's residual streams under bfloat16 compute (residual_dtype)",
    )
    p.add_argument(
        "--unpad-language-model",
        action="store_true",
        help="the language model once per sample at its own length (unpad_language_model)",
    )
    p.add_argument(
        "--compile-layers",
        choices=["none", "all", "vision", "language"],
        default="none",
        help="torch.compile the backbone's vision blocks and/or decoder layers (compile_layers)",
    )


def with_padding_mask(policy) -> None:
    """Give the language model the padding mask in training too (the A/B of ``run_backbone``, which
    leaves it out without a KV cache so that SDPA may pick its causal flash kernel)."""
    lm, run = policy.vlm.model.language_model, policy.run_backbone
    forward = lm.forward

    def run_backbone(seq, *args, **kwargs):
        lm.forward = lambda **kw: forward(**{**kw, "attention_mask": seq["attention_mask"]})
        try:
            return run(seq, *args, **kwargs)
        finally:
            del lm.forward

    policy.run_backbone = run_backbone


def attention_kernels(vlm) -> str:
    """The backbone's attention implementation and, on CUDA, the SDPA kernels eligible for its text
    attention shapes in bfloat16 without and with a padding mask (PyTorch runs the first eligible of
    flash, memory-efficient, cuDNN, math)."""
    impl = vlm.config._attn_implementation
    if impl != "sdpa" or not torch.cuda.is_available():
        return impl
    from torch.nn.attention import SDPBackend, sdpa_kernel

    tc = vlm.config.text_config
    heads, kv, dim = tc.num_attention_heads, tc.num_key_value_heads, tc.head_dim
    q = torch.randn(2, heads, 512, dim, device="cuda", dtype=torch.bfloat16)
    k = torch.randn(2, kv, 512, dim, device="cuda", dtype=torch.bfloat16)
    mask = torch.ones(2, 1, 512, 512, device="cuda", dtype=torch.bool).tril()
    mask[1, ..., 400:] = False  # a shorter (padded) sequence
    out = []
    for name, m in (("causal", None), ("padded", mask)):
        ok = []
        for b in (
            SDPBackend.FLASH_ATTENTION,
            SDPBackend.EFFICIENT_ATTENTION,
            SDPBackend.CUDNN_ATTENTION,
            SDPBackend.MATH,
        ):
            try:
                with sdpa_kernel(b):
                    torch.nn.functional.scaled_dot_product_attention(
                        q, k, k, attn_mask=m, is_causal=m is None, enable_gqa=kv != heads
                    )
                ok.append(b.name.lower())
            except RuntimeError:
                pass
        out.append(f"{name}: {ok[0] if ok else 'none'} (eligible: {', '.join(ok)})")
    return f"sdpa; {'; '.join(out)}"


def synthetic_setup(cfg: ActiveArenaOFTConfig, batch_size: int, episode_frames: int, all_valid: bool):
    """The policy, its preprocessor and an endless iterator of dataset-shaped random batches: K
    stride-16 history frames + the current one, the history present as at a uniformly drawn frame of
    an ``episode_frames`` long episode (``all_valid``: all of it); padded frames are dropped by the
    policy, so they cost nothing."""
    from lerobot.configs.types import FeatureType, PolicyFeature

    from lerobot_activearena.policies.activearena_oft.modeling_activearena_oft import ActiveArenaOFTPolicy

    dim = 18
    cfg.input_features = {
        "observation.images.head": PolicyFeature(FeatureType.VISUAL, (3, 384, 512)),
        "observation.state": PolicyFeature(FeatureType.STATE, (dim,)),
    }
    cfg.output_features = {"action": PolicyFeature(FeatureType.ACTION, (dim,))}
    policy = ActiveArenaOFTPolicy(cfg).to(cfg.device)
    unit = {"mean": torch.zeros(dim), "std": torch.ones(dim), "min": -torch.ones(dim), "max": torch.ones(dim)}
    pre, _ = make_pre_post_processors(cfg, dataset_stats={"observation.state": unit, "action": unit})
    return policy, pre, synthetic_batches(cfg, batch_size, episode_frames, all_valid)


def sweep(policy, pre, cfg, args) -> None:
    """Step time and peak memory per gradient-checkpointing choice, the usual and the all-valid batch,
    on one model and optimizer (their states are allocated by the first step, as in training)."""
    from lerobot_activearena.policies.activearena_vla.helpers import checkpoint_layers

    cuda = args.device.startswith("cuda")
    opt = make_optimizer(policy, args.fused_adamw)
    policy.train()
    print(
        f"sweep: batch {args.batch_size}, K={args.history}, {args.steps} timed steps after {args.warmup} warm-up each"
        + (f"; compiled layers: {args.compile_layers}" if args.compile_layers != "none" else "")
        + ("; fused AdamW" if args.fused_adamw else "")
    )
    # the rows that can meet the memory budget without full checkpointing first: a capped run keeps them
    choices = [
        ("vision", "full", None),
        ("none", "full", None),
        ("all", "full", None),
        ("language", "full", None),
        ("all", "selective", None),
        ("vision", "selective", None),
    ]
    if args.checkpoint_language_layers is not None:
        choices.insert(0, ("all", "full", args.checkpoint_language_layers))
    # the first row once more, untimed, before the rest: a batch shape's first step builds what is
    # built per shape (compiled graphs, kernel choices), which every later row reuses (the same batches)
    for row, (layers, mode, n_language) in enumerate([choices[0], *choices]):
        if mode == "selective" and cfg.compile_layers != "none":
            print(f"checkpointing {layers:>8} {mode:>9}: skipped (does not combine with --compile-layers)")
            continue
        if layers == "none":
            policy.vlm.gradient_checkpointing_disable()
        else:
            checkpoint_layers(policy.vlm, layers, mode, n_language)
        if n_language is not None:
            layers = f"vision+{n_language}L"
        for valid in (False, True):  # the same batches for every choice
            feed = synthetic_batches(cfg, args.batch_size, args.episode_frames, valid)
            if cuda:
                torch.cuda.empty_cache()
                torch.cuda.reset_peak_memory_stats()
            times, images = [], 0
            try:
                for step in range(args.steps + args.warmup):
                    _, seconds, batch = train_step(policy, pre, opt, next(feed), cuda)
                    if step >= args.warmup:  # warm-up: lazy initialisation, compilation for new shapes
                        times.append(seconds)
                    images = int(batch["observation.vlm.frame_valid"].sum())
                step_s = sum(times) / len(times)
                result = f"{step_s:.3f} s/step, {args.batch_size / step_s:.2f} samples/s"
            except torch.OutOfMemoryError:
                batch = None
                opt.zero_grad(set_to_none=True)
                result = "out of memory"
            print(
                ("warm-up (untimed) " if row == 0 else "")
                + f"checkpointing {layers:>8} {mode:>9}, {'all-valid' if valid else 'usual':>9} batch ({images:>3} images): "
                f"{result}; peak {peak_memory(cuda)}",
                flush=True,
            )


def synthetic_batches(cfg, batch_size: int, episode_frames: int, all_valid: bool):
    """Dataset-shaped random batches (see ``synthetic_setup``)."""
    from lerobot_activearena.annotations.keyframes import STRIDE

    dim, history = 18, cfg.history
    g = torch.Generator().manual_seed(0)
    while True:
        t = torch.randint(0, episode_frames, (batch_size,), generator=g)
        present = torch.full_like(t, history) if all_valid else torch.clamp(t // STRIDE, max=history)
        slot = torch.arange(history + 1)[None]
        yield {
            "observation.images.head": torch.rand(batch_size, history + 1, 3, 384, 512, generator=g),
            "observation.images.head_is_pad": slot < (history - present)[:, None],
            "observation.state": torch.randn(batch_size, history + 1, dim, generator=g),
            "action": torch.randn(batch_size, cfg.chunk_size, dim, generator=g),
            "action_is_pad": torch.zeros(batch_size, cfg.chunk_size, dtype=torch.bool),
            "task": ["Press the bell's top center using the left arm."] * batch_size,
        }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--vlm-path", help="default: a tiny random Qwen3-VL written to a temp dir")
    p.add_argument("--root", type=Path, help="an ActiveArena dataset (default: build 2 tasks x 1 episode)")
    p.add_argument("--repo-id", default="local/oft_bench")
    p.add_argument("--device", default="cpu")
    p.add_argument("--batch-size", type=int, default=2)
    p.add_argument("--history", type=int, default=12)
    p.add_argument("--memory", default="chunk")
    p.add_argument("--think", default="subtask")
    p.add_argument("--steps", type=int, default=5)
    p.add_argument(
        "--policy-type",
        choices=list(CONFIGS),
        default="activearena_oft",
        help="the head: OFT regression, GR00T flow-matching DiT, FAST tokens, Plan's executor or planner",
    )
    p.add_argument(
        "--action-tokens",
        type=int,
        default=26,
        help="activearena_fast: action tokens decoded per chunk (p95 on the preview release: 26); the "
        "tiny random backbone never ends its answer, so the budget is what it decodes",
    )
    p.add_argument(
        "--plan-tokens", type=int, default=64, help="activearena_plan: planner answer tokens per chunk"
    )
    p.add_argument(
        "--dit",
        choices=["paper", "tiny"],
        default="paper",
        help="activearena_groot's head: the paper's DiT-B (152 M parameters) or the tests' tiny one",
    )
    p.add_argument("--gradient-checkpointing", action="store_true")
    p.add_argument(
        "--checkpoint-layers",
        choices=["all", "vision", "language"],
        default="all",
        help="with --gradient-checkpointing: the blocks that recompute (gradient_checkpointing_layers)",
    )
    p.add_argument(
        "--checkpoint-language-layers",
        type=int,
        default=None,
        metavar="N",
        help="with --gradient-checkpointing and layers all or language: only the first N decoder layers "
        "recompute (gradient_checkpointing_language_layers); with --sweep: one more row, the vision tower "
        "and the first N language layers",
    )
    p.add_argument(
        "--checkpoint-mode",
        choices=["full", "selective"],
        default="full",
        help="with --gradient-checkpointing: recompute everything but the blocks' inputs, or keep their "
        "matmul and attention outputs (gradient_checkpointing_mode)",
    )
    add_memory_options(p)
    p.add_argument(
        "--padding-mask",
        action="store_true",
        help="pass the padding mask to the language model in training (A/B of leaving it out)",
    )
    p.add_argument(
        "--warmup",
        type=int,
        default=1,
        help="untimed steps first (per sweep row and batch): lazy initialisation, compilation",
    )
    p.add_argument("--fused-adamw", action="store_true", help="torch's fused AdamW kernel (CUDA)")
    p.add_argument(
        "--sweep",
        action="store_true",
        help="--synthetic: one model, then --steps timed steps for each checkpointing choice (all, vision, "
        "language in full; all, vision selectively; none) with the usual and the all-valid batch; peak memory of each (OOM is reported)",
    )
    p.add_argument(
        "--profile", action="store_true", help="print the top operators of one training step (torch.profiler)"
    )
    p.add_argument(
        "--count-ops",
        action="store_true",
        help="count the operators one training step dispatches (kernel launches on a GPU) and its host syncs",
    )
    p.add_argument(
        "--decode-tokens", type=int, default=32, help="greedy <think> tokens per chunk (subtask_max_tokens)"
    )
    p.add_argument(
        "--skip-uncached", action="store_true", help="do not time the re-encoding reference decoder"
    )
    p.add_argument(
        "--dtype", default="auto", help="compute: auto (bfloat16 autocast on CUDA) | float32 | bfloat16"
    )
    p.add_argument(
        "--weights-dtype", default="float32", help="parameters: float32 (master weights) | bfloat16"
    )
    p.add_argument(
        "--synthetic",
        action="store_true",
        help="random batches shaped like the dataset's (no dataset build: runs on a bare GPU machine), "
        "history frames present as at a random frame of an --episode-frames long episode",
    )
    p.add_argument(
        "--episode-frames", type=int, default=166, help="synthetic episodes' length (paper data: 166)"
    )
    p.add_argument(
        "--all-valid", action="store_true", help="synthetic worst case: every history frame present"
    )
    args = p.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="aa_oft_bench_"))
    vlm = args.vlm_path or str(make_tiny_vlm(tmp / "tiny_vlm"))
    think, memory, kind = args.think, args.memory, args.policy_type
    if args.synthetic and kind in ("activearena_fast", "activearena_planner", "activearena_plan"):
        raise SystemExit(f"--synthetic has no annotations or action statistics for {kind}; use a dataset")
    if args.synthetic and think == "subtask":
        think = "instruction"  # no annotations to read the subtask from; a think span of similar length
        print("synthetic batches: think=instruction stands in for think=subtask (same loss, similar length)")
    head = {}
    if kind == "activearena_groot" and args.dit == "tiny":
        head = {"dit_width": 32, "dit_depth": 2, "dit_heads": 2, "dit_queries": 4, "dit_out_dim": 32}
        head |= {"decoder_width": 32, "noise_repeats": 2}
    if kind == "activearena_planner":
        head, think, memory = {"use_state": False, "plan_max_tokens": args.plan_tokens}, "subtask", "chunk"
    if kind == "activearena_plan":  # the executor: retrieved frames (up to K), no think target
        think, memory = "none", "planned"
    root = args.root
    if root is None and not args.synthetic:
        root = tmp / "ds"
        plan = BuildPlan(
            repo_id=args.repo_id,
            split="id",
            tasks=["click_bell_rotate_view", "count_target_press_button"],
            episodes=1,
            episodes_per_shard=1,
        )
        build_dataset(plan, root, workers=2, progress=False)
    if kind == "activearena_fast":
        from lerobot_activearena.cli.fit_fast_tokenizer import fit

        fit(["--repo-id", args.repo_id, "--root", str(root), "--out", str(tmp / "fast"), "--holdout", "2"])
        head = {"action_tokenizer_path": str(tmp / "fast"), "max_action_tokens": args.action_tokens}
    cfg = CONFIGS[kind](
        **head,
        vlm_path=vlm,
        device=args.device,
        memory=memory,
        history=args.history,
        think=think,
        gradient_checkpointing=args.gradient_checkpointing,
        gradient_checkpointing_layers=args.checkpoint_layers,
        gradient_checkpointing_mode=args.checkpoint_mode,
        gradient_checkpointing_language_layers=args.checkpoint_language_layers,
        unpad_language_model=args.unpad_language_model,
        residual_dtype=args.residual_dtype,
        compile_layers=args.compile_layers,
        dtype=args.dtype,
        weights_dtype=args.weights_dtype,
        subtask_max_tokens=args.decode_tokens,
    )
    if args.synthetic:
        if memory != "chunk":
            raise SystemExit(
                "--synthetic draws chunk-memory batches; use --memory chunk (or a dataset via --root)"
            )
        policy, pre, batches = synthetic_setup(cfg, args.batch_size, args.episode_frames, args.all_valid)
        ds = None
        if args.padding_mask:
            with_padding_mask(policy)
        if args.sweep:
            return sweep(policy, pre, cfg, args)
    else:
        meta = LeRobotDatasetMetadata(args.repo_id, root=root)
        policy = make_policy(cfg, ds_meta=meta)
        pre, _ = make_pre_post_processors(cfg, dataset_stats=meta.stats)
        ds = LeRobotDataset(
            args.repo_id,
            root=root,
            video_backend="pyav",
            delta_timestamps=resolve_delta_timestamps(cfg, meta),
        )
        g = torch.Generator().manual_seed(0)
        batches = iter(
            torch.utils.data.DataLoader(
                ds, batch_size=args.batch_size, shuffle=True, generator=g, drop_last=True
            )
        )
    loader = batches
    opt = make_optimizer(policy, args.fused_adamw)
    cuda = args.device.startswith("cuda")
    policy.train()  # from_pretrained leaves the backbone in eval mode, where gradient checkpointing is off
    times, prep, images = [], [], 0
    for step in range(args.steps + args.warmup if args.steps else 0):  # --steps 0: inference only
        prep_s, seconds, batch = train_step(policy, pre, opt, next(loader), cuda)
        if step >= args.warmup:  # warm-up: lazy initialisation, compilation for new shapes
            times.append(seconds)
            prep.append(prep_s)
        images = int(batch["observation.vlm.frame_valid"].sum())
    if args.profile and args.steps:  # one more step, under the profiler (not in the times above)
        activities = [torch.profiler.ProfilerActivity.CPU]
        activities += [torch.profiler.ProfilerActivity.CUDA] if cuda else []
        with torch.profiler.profile(activities=activities) as prof:
            train_step(policy, pre, opt, next(loader), cuda)
        sort = "cuda_time_total" if cuda else "cpu_time_total"
        print(prof.key_averages().table(sort_by=sort, row_limit=25, max_name_column_width=60))
    if args.count_ops and args.steps:  # one more step, every dispatched operator counted
        count = OperatorCount(cpu=not cuda)
        with count:
            train_step(policy, pre, opt, next(loader), cuda)
        print(
            f"one training step dispatches {sum(count.calls.values())} operators "
            f"(most a kernel launch on a GPU), {count.calls['aten._local_scalar_dense.default']} of "
            "them reads of a tensor's value (.item(), bool() or .tolist()); "
            + (
                f"{sum(count.sync_sites.values())} of device tensors (host syncs), the most from:"
                if cuda
                else "the most from (on a GPU, a host sync where the tensor is on the device):"
            )
        )
        for where, n in count.sync_sites.most_common(8):
            print(f"  {n:>5}  {where}")
    n_params = sum(p.numel() for p in policy.parameters())
    peak = peak_memory(cuda)
    head_params = sum(p.numel() for n, p in policy.named_parameters() if not n.startswith("vlm."))
    print(
        f"{kind}: action head, state encoder and queries {head_params / 1e6:.2f} M parameters"
        + (f" (DiT: {args.dit})" if kind == "activearena_groot" else "")
    )
    print(
        f"model {vlm}: {n_params / 1e6:.1f} M parameters, device {args.device}, batch {args.batch_size}, "
        f"K={args.history} ({memory} memory), think={think}"
    )
    print(
        f"precision: {'bfloat16 autocast' if cfg.autocast_bfloat16 else 'float32'} compute, "
        f"{next(policy.vlm.parameters()).dtype} weights; gradient checkpointing "
        + (
            f"of {args.checkpoint_layers} layers, {args.checkpoint_mode}"
            if args.gradient_checkpointing
            else "off"
        )
        + ("; fused AdamW" if args.fused_adamw else "")
        + ("; padding mask in training" if args.padding_mask else "")
        + ("; language model per sample (unpadded)" if args.unpad_language_model else "")
        + f"; residual streams {args.residual_dtype}"
        + (f"; compiled layers: {args.compile_layers}" if args.compile_layers != "none" else "")
    )
    print(f"attention: {attention_kernels(policy.vlm)}")
    if times:
        step_s, prep_s = sum(times) / len(times), sum(prep) / len(prep)
        print(
            f"train step (preprocess + forward + backward + AdamW): {step_s:.3f} s mean over {len(times)} steps "
            f"(preprocessing {prep_s:.3f} s of it: the training loop's own process, images on {args.device}); "
            f"{args.batch_size / step_s:.2f} samples/s; "
            f"images in the last batch: {images}; peak memory: {peak}"
        )
    if kind == "activearena_planner":
        return  # the planner acts only inside activearena_plan: its inference is timed there
    if kind == "activearena_plan":  # a planner (same backbone size) for the executor to run
        planner_cfg = ActiveArenaPlannerConfig(
            vlm_path=vlm, device=args.device, dtype=args.dtype, plan_max_tokens=args.plan_tokens
        )
        make_policy(planner_cfg, ds_meta=meta).save_pretrained(tmp / "planner")
        policy.config.planner_path = str(tmp / "planner")
    policy.eval()
    policy.reset()
    item = (
        dict(ds[len(ds) // 2].items())
        if ds is not None
        else {k: (v[0] if k != "task" else v[0]) for k, v in next(loader).items()}
    )
    image, state = item["observation.images.head"], item["observation.state"]
    obs = {
        "observation.images.head": (image[-1] if image.dim() == 4 else image)[None],  # the current frame,
        "observation.state": (state[-1] if state.dim() == 2 else state)[None],  # as an env batch of 1
        "task": [item["task"]],
    }

    def timed(fn):
        if cuda:
            torch.cuda.synchronize()
        t0 = time.perf_counter()
        out = fn()
        if cuda:
            torch.cuda.synchronize()
        return time.perf_counter() - t0, out

    # chunk boundary with an empty memory, then one with a full bank (K frames, as K chunk boundaries
    # of memory=chunk would have written; their content does not change the compute)
    from lerobot_activearena.policies.activearena_vla import processor_activearena_vla

    policy.reset()
    b = pre(dict(obs))
    lat = [timed(lambda: policy.select_action(b))[0]]
    pixels, grid = policy.memory_pixels(b)  # as the memory keeps a frame
    entry = {"pixels": pixels[0], "grid": grid[0], "state": b["observation.state"][0]}
    full = 16 * args.history
    if kind == "activearena_plan":  # K + 1 stride frames stored, K of them retrieved into the bank
        policy._frames[0] = {16 * k: dict(entry, planner={}) for k in range(args.history + 1)}
        policy._banks[0].frames = [16 * k for k in range(args.history)]
    else:
        policy._bank[0] = [dict(entry, t=16 * k) for k in range(args.history)]
    for _ in range(2):  # cold: every memory frame through the vision tower; warm: their features reused
        policy._queue.clear()
        policy._t = full
        lat.append(timed(lambda: policy.select_action(b))[0])
    peak = peak_memory(cuda)
    what = {
        "activearena_fast": f" (greedy decoding of {args.decode_tokens} think + {args.action_tokens} action + 8 tag "
        "tokens: the random backbone never ends its answer)",
        "activearena_plan": f" (planner: {args.history + 1} frames and {args.plan_tokens} answer tokens; executor: "
        f"{args.history} retrieved frames + the current one)",
    }.get(kind, "")
    print(
        f"inference per chunk{what}: {lat[2] * 1000:.0f} ms with {args.history} memory frames + the current one "
        f"(memory frames' vision features reused, as in an episode), {lat[1] * 1000:.0f} ms encoding all "
        f"{args.history + 1} images, {lat[0] * 1000:.0f} ms with the current frame only; peak memory so far: {peak}"
    )
    if args.think == "subtask" and kind in (
        "activearena_oft",
        "activearena_groot",
    ):  # what memory=subtask adds per chunk: greedy <think> decoding
        pixels, grid, valid, state, cache = policy.history_batch(b)
        enc = policy.encode_args(
            pixels,
            grid,
            valid,
            state,
            b[processor_activearena_vla.PREFIX_IDS],
            b[processor_activearena_vla.PROMPT_IDS],
            b[processor_activearena_vla.PROMPT_MASK],
        )
        with torch.no_grad():
            cached, (tokens, _, _) = timed(
                lambda: policy.greedy_think(enc, use_cache=True, vision_cache=cache)
            )
            line = (
                f"subtask decoding ({len(tokens[0])} tokens, {args.history} memory frames): {cached * 1000:.0f} ms "
                "with the KV cache and the memory's vision features (the same pass also gives the chunk)"
            )
            if not args.skip_uncached:
                full = timed(lambda: policy.greedy_think(enc, use_cache=False))[0]
                line += f", {full * 1000:.0f} ms re-encoding everything every step ({full / cached:.1f}x)"
        print(line)


if __name__ == "__main__":
    main()
