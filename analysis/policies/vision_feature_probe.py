"""Do a vision tower's features of a frame hold what the count needs? For each vision cache
(`activearena-cache-vision`) of a count build, a small probe (a per-token MLP whose outputs are
summed over the frame's tokens) learns the number of counted objects in view (green blocks by
default) from the frame's visual tokens, on the counting subtask's frames of episodes 0-159; it
prints train and held-out (episodes 160+) accuracy beside the majority class. On the one-arm count
build the focus-grounded tower's cache does not beat the majority class held out (46.3 % against
48.2 %); the tower grounded also on the blocks (`activearena-ground-vision --search-weight 1`) does
(75.7 %).

    python analysis/policies/vision_feature_probe.py --root outputs/datasets/cpu_count_left_200_p16_192 \\
        outputs/vision_cache/cpu_count_left_200_p16_192_grounded.safetensors CACHE...
"""

from __future__ import annotations

import argparse
import glob
import json
from pathlib import Path

import numpy as np
import torch


def objects_in_view(root: Path, prefix: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per frame of the build (in dataset index order): how many objects whose key starts with
    ``prefix`` are visible, the subtask index and the episode index."""
    import pandas as pd

    data = pd.concat(pd.read_parquet(f) for f in sorted(glob.glob(f"{root}/data/*/*.parquet")))
    data = data.sort_values("index")
    counted = {}
    for path in sorted((root / "meta/activearena/sidecars").glob("episode_*.json")):
        sidecar = json.loads(path.read_text())
        counted[int(path.stem.split("_")[1])] = [
            o["index"] for o in sidecar["objects"] if o["key"].startswith(prefix)
        ]
    visible = np.stack(data["visible_object_mask"].to_numpy()) == 1
    episodes = data["episode_index"].to_numpy()
    n = np.array([visible[i, counted[e]].sum() for i, e in enumerate(episodes)])
    return n, data["subtask_index"].to_numpy(), episodes


def probe(tokens: torch.Tensor, labels: torch.Tensor, train: torch.Tensor, steps: int = 600, seed: int = 0):
    """Fit the per-token MLP probe on the ``train`` rows of (N, T, D) ``tokens``; returns the fitted
    probe's predicted class for every row."""
    mean, std = tokens[train].mean((0, 1)), tokens[train].std((0, 1)) + 1e-6
    x = (tokens - mean) / std
    torch.manual_seed(seed)
    width = x.shape[-1]
    head = torch.nn.Sequential(
        torch.nn.Linear(width, width), torch.nn.GELU(), torch.nn.Linear(width, int(labels.max()) + 1)
    )
    opt = torch.optim.Adam(head.parameters(), lr=1e-3, weight_decay=1e-4)
    rows = torch.nonzero(train)[:, 0]
    for _ in range(steps):
        batch = rows[torch.randint(0, len(rows), (512,))]
        opt.zero_grad()
        torch.nn.functional.cross_entropy(head(x[batch]).sum(1), labels[batch]).backward()
        opt.step()
    with torch.no_grad():
        return head(x).sum(1).argmax(1)


def cache_tokens(cache: Path, frames: int) -> torch.Tensor:
    """A vision cache's (N, T, D) tokens as float; refuses a cache of another build (not ``frames`` long)."""
    from safetensors import safe_open

    tokens = safe_open(str(cache), "pt").get_tensor("embeds").float()
    if len(tokens) != frames:
        raise SystemExit(f"{cache} holds {len(tokens)} frames, the build {frames}: a cache of another build")
    return tokens


def main(argv: list[str] | None = None) -> None:

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument(
        "caches", nargs="+", type=Path, help="vision caches of the build (activearena-cache-vision)"
    )
    p.add_argument("--root", type=Path, required=True, help="the full build (with its annotations)")
    p.add_argument("--objects", default="green_block", help="key prefix of the counted objects")
    p.add_argument("--subtask", type=int, default=1, help="the counting subtask's index")
    p.add_argument("--heldout-from", type=int, default=160, help="episodes from this one are held out")
    args = p.parse_args(argv)
    n, subtask, episodes = objects_in_view(args.root, args.objects)
    frames = subtask == args.subtask
    train = torch.tensor(frames & (episodes < args.heldout_from))
    test = torch.tensor(frames & (episodes >= args.heldout_from))
    labels = torch.tensor(n)
    majority = torch.bincount(labels[train]).argmax()
    print(
        f"{int(frames.sum())} counting frames; {args.objects} in view: {np.bincount(n[frames]).tolist()} (0, 1, 2...)"
    )
    print("| vision cache | train accuracy | held-out accuracy | majority class, held out |")
    print("|---|---|---|---|")
    for cache in args.caches:
        tokens = cache_tokens(cache, len(n))
        pred = probe(tokens, labels, train)
        acc = [(pred[m] == labels[m]).float().mean().item() for m in (train, test)]
        print(
            f"| {cache} | {acc[0]:.3f} | {acc[1]:.3f} | {(labels[test] == majority).float().mean().item():.3f} |"
        )


if __name__ == "__main__":
    main()
