"""Sample-loading cost of a built dataset against its slim copy (``activearena-slim-dataset``), for
the sample a LeRobot ACT / diffusion policy draws (the head image, the state and a 16-step action
chunk) or, with ``--vla``, the sample the chunk-memory ActiveArena-VLA draws (13 head images and
states at stride 16, 16 actions) against the ``--vla`` copy; in the process, one thread:

    python benchmarks/slim_dataset_loading.py --root outputs/datasets/cpu_click_bell
    python benchmarks/slim_dataset_loading.py --root outputs/datasets/cpu_count_192 --vla

Prints ms per sample for both and the full dataset's cost as a ratio of the slim one's (the
machine's noise cancels out of the ratio).
"""

from __future__ import annotations

import argparse
import random
import tempfile
import time
from pathlib import Path

import torch
from lerobot.datasets.lerobot_dataset import LeRobotDataset

from lerobot_activearena.cli.slim_dataset import slim_dataset, vla_columns
from lerobot_activearena.datasets_build.features import FPS, IMAGE_KEY
from lerobot_activearena.policies.activearena_oft.configuration_activearena_oft import ActiveArenaOFTConfig

_OFT = ActiveArenaOFTConfig(device="cpu")  # the presets' chunk memory: K = 12, stride 16, chunk 16
CHUNK = [k / FPS for k in _OFT.action_delta_indices]
HISTORY = [k / FPS for k in _OFT.observation_delta_indices]
ACT_SAMPLE = {"action": CHUNK}
VLA_SAMPLE = {IMAGE_KEY: HISTORY, "observation.state": HISTORY, "action": CHUNK}


def ms_per_sample(root: Path, samples: int, delta: dict, seed: int = 0) -> tuple[float, int]:
    ds = LeRobotDataset(f"local/{root.name}", root=root, delta_timestamps=delta)
    order = random.Random(seed).sample(range(len(ds)), samples + 1)
    ds[order[0]]  # open the decoder outside the timing
    t = time.perf_counter()
    for i in order[1:]:
        ds[i]
    return 1000 * (time.perf_counter() - t) / samples, len(ds.meta.features)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--root", required=True, help="a dataset activearena-build-dataset wrote")
    p.add_argument("--samples", type=int, default=200)
    p.add_argument("--vla", action="store_true", help="the chunk-memory VLA's sample and the --vla copy")
    args = p.parse_args()
    torch.set_num_threads(1)
    delta = VLA_SAMPLE if args.vla else ACT_SAMPLE
    with tempfile.TemporaryDirectory() as tmp:
        slim = Path(tmp) / "slim"
        slim_dataset(args.root, slim, keep=vla_columns() if args.vla else ())
        full_ms, full_cols = ms_per_sample(Path(args.root), args.samples, delta)
        slim_ms, slim_cols = ms_per_sample(slim, args.samples, delta)
    print(f"full dataset ({full_cols} columns): {full_ms:.1f} ms/sample")
    print(f"slim copy    ({slim_cols} columns): {slim_ms:.1f} ms/sample")
    print(f"full / slim: {full_ms / slim_ms:.2f}x")


if __name__ == "__main__":
    main()
