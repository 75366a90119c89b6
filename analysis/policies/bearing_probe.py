"""How precisely does a vision tower's table (``activearena-cache-vision``) hold where the picked
object lies in view? On an inspect-and-place build, a ridge probe on each frame's visual tokens
(embeddings and deepstack features, flattened) learns the inspected object's bearing from the
torso's heading (degrees round from straight ahead: its placement's azimuth from the base less the
torso's yaw) on the first ``--frames`` frames of the training episodes, and predicts it on held-out
episodes (the last ``--holdout`` share). A policy whose first turn is off by more than the probe's
held-out error does not use all its tower gives; one off by about as much is held back by the tower.
Prints one JSON line per alpha (the chosen one, by 5-fold episode cross-validation, marked) with
the held-out median and 90th-percentile absolute error, the spread of the bearing itself (the error
of always guessing the mean) and, on each of ``--report-frames`` alone, the same and the median
error of objects nearly ahead (bearing within 15 deg) and far round (30 deg or more).

    python analysis/policies/bearing_probe.py --root outputs/datasets/cpu_block_cf_600_p16_192_vla \\
        outputs/vision_cache/cpu_block_cf_600_p16_192_grounded.safetensors

``--test-root R --test-cache C``: fit on all of the first build's episodes and score on another
build's table of the same tower (a ``--turn-error`` build's frame 16 shows the torso off its turn).
"""

from __future__ import annotations

import argparse
import glob
import json
from pathlib import Path

import numpy as np

from lerobot_activearena.sim.action import TORSO_YAW

ALPHAS = (1.0, 10.0, 100.0, 1000.0, 10000.0)


def bearings(root: Path, frames: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The dataset indices of every episode's first ``frames`` frames, their episode, frame index,
    and the inspected object's bearing from the torso's heading (degrees)."""
    import pandas as pd

    cols = ["index", "episode_index", "frame_index", "observation.state"]
    data = pd.concat(pd.read_parquet(f, columns=cols) for f in sorted(glob.glob(f"{root}/data/*/*.parquet")))
    data = data[data["frame_index"] < frames].sort_values("index")
    azimuth = {}
    for path in sorted((root / "meta/activearena/sidecars").glob("episode_*.json")):
        side = json.loads(path.read_text())
        inspected = (side.get("expert_notes") or {}).get("inspections") or []
        if not inspected:
            raise ValueError(f"{path} records no inspection: bearing_probe needs an inspect-and-place build")
        place = {p["name"]: p for p in side["placements"]}[inspected[0]["object"]]
        azimuth[int(path.stem.split("_")[1])] = place["angle"] - 90.0
    yaw = np.degrees(np.stack(data["observation.state"].to_numpy())[:, TORSO_YAW])
    episodes = data["episode_index"].to_numpy()
    bearing = np.array([azimuth[int(e)] for e in episodes]) - yaw
    return data["index"].to_numpy(), episodes, data["frame_index"].to_numpy(), bearing


def features(cache: Path, index: np.ndarray) -> np.ndarray:
    """(len(index), tokens * width * 2): each frame's embeddings and deepstack features, flattened."""
    from safetensors import safe_open

    rows = []
    with safe_open(str(cache), "pt") as f:
        embeds, deep = f.get_slice("embeds"), f.get_slice("deepstack")
        starts = np.flatnonzero(np.diff(index, prepend=-2) != 1)  # runs of consecutive indices
        for a, b in zip(starts, [*starts[1:], len(index)], strict=True):
            lo, hi = int(index[a]), int(index[b - 1]) + 1
            e = embeds[lo:hi].numpy().reshape(hi - lo, -1)
            d = deep[:, lo:hi].numpy().transpose(1, 0, 2, 3).reshape(hi - lo, -1)
            rows.append(np.concatenate([e, d], axis=1))
    return np.concatenate(rows)


def ridge(x: np.ndarray, y: np.ndarray, alpha: float) -> tuple[np.ndarray, float]:
    xm, ym = x.mean(0), y.mean()
    xc = x - xm
    w = np.linalg.solve(xc.T @ xc + alpha * np.eye(x.shape[1]), xc.T @ (y - ym))
    return w, float(ym - xm @ w)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cache", type=Path)
    ap.add_argument("--root", type=Path, required=True, help="the build the cache was made from")
    ap.add_argument("--frames", type=int, default=16, help="each episode's first N frames (default 16)")
    ap.add_argument("--holdout", type=float, default=0.2, help="held-out share of episodes (the last)")
    ap.add_argument("--test-root", type=Path, help="score on this build instead of held-out episodes")
    ap.add_argument("--test-cache", type=Path, help="its table of the same tower (with --test-root)")
    ap.add_argument("--report-frames", default="0,8,15", help="frame indices reported alone (default 0,8,15)")
    args = ap.parse_args()
    if (args.test_root is None) != (args.test_cache is None):
        ap.error("--test-root and --test-cache go together: the other build and its table of the same tower")
    index, episodes, frame, y = bearings(args.root, args.frames)
    x = features(args.cache, index)
    eps = np.unique(episodes)
    held = np.isin(episodes, eps[int(len(eps) * (1 - args.holdout)) :])
    if args.test_root is not None:
        t_index, t_episodes, t_frame, t_y = bearings(args.test_root, args.frames)
        x = np.concatenate([x, features(args.test_cache, t_index)])
        episodes = np.concatenate([episodes, t_episodes + episodes.max() + 1])
        frame, y = np.concatenate([frame, t_frame]), np.concatenate([y, t_y])
        held = np.arange(len(y)) >= len(index)
    x = (x - x[~held].mean(0)) / (x[~held].std(0) + 1e-6)
    train = np.flatnonzero(~held)
    folds = np.array_split(np.unique(episodes[train]), 5)
    cv = {}
    for alpha in ALPHAS:
        errs = []
        for fold in folds:
            out = np.isin(episodes[train], fold)
            w, b = ridge(x[train[~out]], y[train[~out]], alpha)
            errs.append(np.abs(x[train[out]] @ w + b - y[train[out]]))
        cv[alpha] = float(np.median(np.concatenate(errs)))
    best = min(cv, key=cv.get)
    for alpha in ALPHAS:
        w, b = ridge(x[train], y[train], alpha)
        err = np.abs(x[held] @ w + b - y[held])
        spread = np.abs(y[held] - y[train].mean())
        row = {
            "cache": args.cache.name,
            "alpha": alpha,
            "chosen": alpha == best,
            "cv_median_deg": round(cv[alpha], 2),
            "frames": args.frames,
            "held_out_episodes": int(len(np.unique(episodes[held]))),
            "median_error_deg": round(float(np.median(err)), 2),
            "p90_error_deg": round(float(np.percentile(err, 90)), 2),
            "guess_mean_median_deg": round(float(np.median(spread)), 2),
        }
        for f in (int(v) for v in args.report_frames.split(",")):
            at, ahead = frame[held] == f, np.abs(y[held]) < 15
            row[f"frame{f}"] = {
                "median_error_deg": _median(err[at]),
                "p90_error_deg": round(float(np.percentile(err[at], 90)), 2) if at.any() else None,
                "ahead_median_error_deg": _median(err[at & ahead]),
                "far_median_error_deg": _median(err[at & (np.abs(y[held]) >= 30)]),
            }
        print(json.dumps(row))


def _median(v: np.ndarray) -> float | None:
    return round(float(np.median(v)), 2) if len(v) else None


if __name__ == "__main__":
    main()
