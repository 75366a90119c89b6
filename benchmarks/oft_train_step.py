"""activearena_oft training-step time, peak memory and inference latency per chunk.

    python benchmarks/oft_train_step.py                      # tiny random Qwen3-VL on the CPU
    python benchmarks/oft_train_step.py --vlm-path Qwen/Qwen3-VL-2B-Instruct --device cuda --batch-size 7

Builds a small ActiveArena dataset (or uses --root), runs the real LeRobot factories
(make_policy, make_pre_post_processors, the dataset with the config's delta_timestamps), and times
preprocess + forward + backward + AdamW step at the given batch size with K history frames, then
``select_action`` latency at a chunk boundary (one chunk = one VLM forward) and, with think=subtask,
the greedy ``<think>`` decoding that memory=subtask adds per chunk (KV-cached vs re-encoding). Peak memory is
``torch.cuda.max_memory_allocated`` on CUDA and the process's peak RSS on the CPU.
"""

from __future__ import annotations

import argparse
import resource
import tempfile
import time
from pathlib import Path

import torch
from lerobot.datasets.dataset_metadata import LeRobotDatasetMetadata
from lerobot.datasets.factory import resolve_delta_timestamps
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.policies.factory import make_policy, make_pre_post_processors

from lerobot_activearena.datasets_build.pipeline import build_dataset
from lerobot_activearena.datasets_build.plan import BuildPlan
from lerobot_activearena.policies.activearena_oft.configuration_activearena_oft import ActiveArenaOFTConfig
from lerobot_activearena.policies.activearena_oft.tiny_vlm import make_tiny_vlm


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
    p.add_argument("--gradient-checkpointing", action="store_true")
    args = p.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="aa_oft_bench_"))
    vlm = args.vlm_path or str(make_tiny_vlm(tmp / "tiny_vlm"))
    root = args.root
    if root is None:
        root = tmp / "ds"
        plan = BuildPlan(repo_id=args.repo_id, split="id", tasks=["click_bell_rotate_view", "count_target_press_button"],
                         episodes=1, episodes_per_shard=1)
        build_dataset(plan, root, workers=2, progress=False)
    meta = LeRobotDatasetMetadata(args.repo_id, root=root)
    cfg = ActiveArenaOFTConfig(vlm_path=vlm, device=args.device, memory=args.memory, history=args.history,
                               think=args.think, gradient_checkpointing=args.gradient_checkpointing)
    policy = make_policy(cfg, ds_meta=meta)
    pre, _ = make_pre_post_processors(cfg, dataset_stats=meta.stats)
    ds = LeRobotDataset(args.repo_id, root=root, video_backend="pyav", delta_timestamps=resolve_delta_timestamps(cfg, meta))
    g = torch.Generator().manual_seed(0)
    loader = iter(torch.utils.data.DataLoader(ds, batch_size=args.batch_size, shuffle=True, generator=g, drop_last=True))
    opt = torch.optim.AdamW(policy.get_optim_params(), betas=(0.9, 0.95), eps=1e-8, weight_decay=1e-8)
    cuda = args.device.startswith("cuda")
    times, images = [], 0
    for step in range(args.steps + 1):
        raw = next(loader)
        if cuda:
            torch.cuda.synchronize()
        t0 = time.perf_counter()
        batch = pre(raw)
        loss, _ = policy.forward(batch)
        opt.zero_grad()
        loss.backward()
        torch.nn.utils.clip_grad_norm_(policy.parameters(), 1.0)
        opt.step()
        if cuda:
            torch.cuda.synchronize()
        if step:  # the first step includes lazy initialisation
            times.append(time.perf_counter() - t0)
        images = int(batch["observation.vlm.frame_valid"].sum())
    n_params = sum(p.numel() for p in policy.parameters())
    peak = (f"{torch.cuda.max_memory_allocated() / 2**30:.2f} GiB GPU (max_memory_allocated)" if cuda
            else f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20:.2f} GiB peak RSS")
    print(f"model {vlm}: {n_params / 1e6:.1f} M parameters, device {args.device}, batch {args.batch_size}, "
          f"K={args.history} ({args.memory} memory), think={args.think}")
    print(f"train step (preprocess + forward + backward + AdamW): {sum(times) / len(times):.3f} s mean over "
          f"{len(times)} steps; images in the last batch: {images}; peak memory: {peak}")
    policy.eval()
    policy.reset()
    item = {k: v for k, v in ds[len(ds) // 2].items()}
    obs = {"observation.images.head": item["observation.images.head"][-1:], "observation.state": item["observation.state"][-1:],
           "task": [item["task"]]}
    # step through K chunks so the memory bank is full, then time the chunk boundaries
    policy.reset()
    lat = []
    for t in range(16 * args.history + 1):
        b = pre(dict(obs))
        if cuda:
            torch.cuda.synchronize()
        t0 = time.perf_counter()
        policy.select_action(b)
        if cuda:
            torch.cuda.synchronize()
        if t % 16 == 0:
            lat.append(time.perf_counter() - t0)
    print(f"inference: {lat[-1] * 1000:.0f} ms per chunk with {args.history} memory frames + the current "
          f"one ({lat[0] * 1000:.0f} ms with the current frame only)")
    if args.think == "subtask":  # what memory=subtask adds per chunk: greedy <think> decoding
        from lerobot_activearena.policies.activearena_oft import processor_activearena_oft as P

        pixels, grid, valid, state = policy._history_batch(b)
        enc = (pixels, grid, valid, state if policy.state_encoder is not None else None, b[P.PREFIX_IDS],
               b[P.PROMPT_IDS], b[P.PROMPT_MASK])
        dec = {}
        for use_cache in (True, False):
            with torch.no_grad():
                if cuda:
                    torch.cuda.synchronize()
                t0 = time.perf_counter()
                tokens, _ = policy._greedy_think(enc, use_cache=use_cache)
                if cuda:
                    torch.cuda.synchronize()
                dec[use_cache] = (time.perf_counter() - t0, len(tokens[0]))
        print(f"subtask decoding ({dec[True][1]} tokens, {args.history} memory frames): {dec[True][0] * 1000:.0f} ms "
              f"with the KV cache, {dec[False][0] * 1000:.0f} ms re-encoding every step "
              f"({dec[False][0] / dec[True][0]:.1f}x)")


if __name__ == "__main__":
    main()
