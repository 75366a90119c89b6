"""Training-sample throughput of a built ActiveArena dataset: 13 head images (stride-16 history of 12
frames + the current one) and 13 states per sample, through a PyTorch DataLoader.

    python benchmarks/dataloader_throughput.py --root outputs/datasets/bench_id --repo-id local/bench_id
    python benchmarks/dataloader_throughput.py   # builds a small dataset first (2 tasks x 2 episodes)

Prints samples/s for each video decoder (LeRobot's default torchcodec, which needs FFmpeg's shared
libraries: ``scripts/bootstrap.sh`` installs them, and PyAV) and worker count (default: 0 = in the
process, and 2), with LeRobot's own ``LeRobotDataset`` and ``delta_timestamps``, then torchcodec's
speed as a ratio of PyAV's (the machine's noise cancels out of the ratio).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import torch
from lerobot.datasets import video_utils
from lerobot.datasets.lerobot_dataset import LeRobotDataset

from lerobot_activearena.datasets_build.features import FPS, IMAGE_KEY
from lerobot_activearena.datasets_build.pipeline import build_dataset
from lerobot_activearena.datasets_build.plan import BuildPlan
from lerobot_activearena.policies.activearena_oft.configuration_activearena_oft import ActiveArenaOFTConfig

# the presets' chunk memory (K = 12, stride 16)
HISTORY = [k / FPS for k in ActiveArenaOFTConfig(device="cpu").observation_delta_indices]


def measure(ds: LeRobotDataset, workers: int, batch: int, batches: int) -> float:
    if workers:
        # LeRobot keeps torchcodec decoders (with their open files) in a module-level cache; forked
        # workers that inherit decoders the parent used read corrupt packets. lerobot-train's parent
        # decodes nothing before its workers start: start them from an empty cache, as it does.
        video_utils._default_decoder_cache.clear()
    loader = torch.utils.data.DataLoader(
        ds,
        batch_size=batch,
        shuffle=True,
        num_workers=workers,
        generator=torch.Generator().manual_seed(0),
        persistent_workers=False,
        drop_last=True,
    )
    it = iter(loader)
    next(it)  # worker start-up and the first decode are not throughput
    t0 = time.perf_counter()
    n = 0
    for _ in range(batches):
        b = next(it)
        n += b[IMAGE_KEY].shape[0]
    return n / (time.perf_counter() - t0)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--root", type=Path, help="a built dataset (default: build a small one in a temp dir)")
    p.add_argument("--repo-id", default="local/bench_id")
    p.add_argument("--workers", default="0,2", help="comma list of DataLoader worker counts (0: in-process)")
    p.add_argument("--backends", default="torchcodec,pyav", help="comma list of LeRobot video backends")
    p.add_argument("--batch-size", type=int, default=8)
    p.add_argument("--batches", type=int, default=20)
    args = p.parse_args()
    root = args.root
    if root is None:
        root = Path(tempfile.mkdtemp(prefix="aa_loader_")) / "ds"
        plan = BuildPlan(
            repo_id=args.repo_id,
            split="id",
            tasks=["click_bell_rotate_view", "count_target_press_button"],
            episodes=2,
            episodes_per_shard=2,
        )
        build_dataset(plan, root, workers=2, progress=False)
    rates: dict[tuple[str, int], float] = {}
    for backend in args.backends.split(","):
        ds = LeRobotDataset(
            args.repo_id,
            root=root,
            video_backend=backend,
            delta_timestamps={IMAGE_KEY: HISTORY, "observation.state": HISTORY},
        )
        item = ds[len(ds) // 2]
        print(
            f"{backend}: dataset {root}: {ds.num_episodes} episodes, {len(ds)} frames; sample {IMAGE_KEY} "
            f"{tuple(item[IMAGE_KEY].shape)}, observation.state {tuple(item['observation.state'].shape)}"
        )
        for w in [int(x) for x in args.workers.split(",")]:
            sps = rates[backend, w] = measure(ds, w, args.batch_size, args.batches)
            print(
                f"{backend}, workers {w}, batch {args.batch_size}: {sps:.1f} samples/s ({13 * sps:.0f} frames/s)"
            )
    for w in [int(x) for x in args.workers.split(",")]:
        if ("torchcodec", w) in rates and ("pyav", w) in rates:
            print(f"workers {w}: torchcodec / pyav = {rates['torchcodec', w] / rates['pyav', w]:.2f}x")


if __name__ == "__main__":
    main()
