"""`activearena-fit-fast-tokenizer --repo-id ID --root DIR --out OUT`: fit the FAST action tokenizer
on a LeRobotDataset's 16-step action chunks (min-max normalised to [-1, 1] with the dataset's own
statistics, as the FAST policy normalises them) and save it; prints tokens per chunk and the
round-trip error on held-out episodes, and writes them to OUT/fit_report.json."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

HORIZON = 16
EPS = 1e-8  # LeRobot's MIN_MAX normaliser's


def action_chunks(actions: np.ndarray, episodes: np.ndarray, horizon: int = HORIZON) -> np.ndarray:
    """One chunk per frame: its next ``horizon`` actions, the episode's last action repeated past
    its end (LeRobot pads a chunk with the edge frame and flags it)."""
    chunks = []
    for ep in np.unique(episodes):
        a = actions[episodes == ep]
        idx = np.minimum(np.arange(len(a))[:, None] + np.arange(horizon)[None], len(a) - 1)
        chunks.append(a[idx])
    return np.concatenate(chunks)


def normalise(x: np.ndarray, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    return (x - low) / (high - low + EPS) * 2 - 1


def roundtrip_figures(tok, chunks: np.ndarray) -> dict:
    from tqdm import tqdm

    lengths, errors, failed = [], [], 0
    for c in tqdm(chunks, desc="round trip", unit="chunk", leave=False):
        ids = tok.encode(c)
        back = tok.decode(ids)
        lengths.append(len(ids))
        if back is None:
            failed += 1
            continue
        errors.append(np.abs(back - c))
    err = np.stack(errors)
    lengths = np.asarray(lengths)
    return {
        "chunks": len(chunks),
        "codes_per_chunk": tok.horizon * tok.action_dim,
        "tokens_per_chunk_mean": round(float(lengths.mean()), 1),
        "tokens_per_chunk_p95": int(np.percentile(lengths, 95)),
        "tokens_per_chunk_max": int(lengths.max()),
        "abs_error_mean": float(err.mean()),
        "abs_error_p99": float(np.percentile(err, 99)),
        "abs_error_max": float(err.max()),
        "decode_failures": failed,
    }


def main(argv: list[str] | None = None) -> None:
    fit(argv)


def fit(argv: list[str] | None = None) -> dict:
    """The command; returns its report."""
    p = argparse.ArgumentParser(
        prog="activearena-fit-fast-tokenizer", description=__doc__.split("\n\n")[0].split(": ", 1)[1]
    )
    p.add_argument("--repo-id", required=True)
    p.add_argument("--root", type=Path, help="the dataset's local folder (default: LeRobot's cache)")
    p.add_argument("--out", type=Path, required=True, help="folder to save the tokenizer in")
    p.add_argument("--vocab-size", type=int, default=2048)
    p.add_argument("--scale", type=float, default=10.0)
    p.add_argument("--holdout", type=int, default=5, help="every N-th episode is held out for the figures")
    p.add_argument("--overwrite", action="store_true")
    args = p.parse_args(argv)
    from ..policies.activearena_fast.action_tokenizer import CONFIG_FILE, FastActionTokenizer

    if (args.out / CONFIG_FILE).exists() and not args.overwrite:
        p.error(f"{args.out} already holds a FAST tokenizer; pass --overwrite to replace it")
    if args.holdout < 2:
        p.error("--holdout must be >= 2 (every N-th episode is held out)")
    from lerobot.datasets.lerobot_dataset import LeRobotDatasetMetadata

    meta = LeRobotDatasetMetadata(args.repo_id, root=args.root)
    if "action" not in meta.features:
        p.error(f"{args.repo_id} has no 'action' feature")
    import pandas as pd

    files = sorted((Path(meta.root) / "data").glob("**/*.parquet"))
    frames = pd.concat([pd.read_parquet(f, columns=["action", "episode_index"]) for f in files])
    actions = np.stack(frames["action"].to_numpy()).astype(float)
    episodes = frames["episode_index"].to_numpy()
    low, high = np.asarray(meta.stats["action"]["min"], float), np.asarray(meta.stats["action"]["max"], float)
    held = np.isin(episodes, np.unique(episodes)[args.holdout - 1 :: args.holdout])
    if held.all() or not held.any():
        p.error(
            f"--holdout {args.holdout} leaves {'no' if held.all() else 'no held-out'} episodes to "
            f"{'fit on' if held.all() else 'measure on'} among the dataset's {len(np.unique(episodes))}; "
            "pick a smaller --holdout"
        )
    fit_chunks = normalise(action_chunks(actions[~held], episodes[~held]), low, high)
    test_chunks = normalise(action_chunks(actions[held], episodes[held]), low, high)
    print(
        f"{args.repo_id}: {len(np.unique(episodes))} episodes, {len(actions)} frames; fitting on "
        f"{len(fit_chunks)} chunks, {len(test_chunks)} held out"
    )
    tok = FastActionTokenizer.fit(fit_chunks, vocab_size=args.vocab_size, scale=args.scale)
    tok.save_pretrained(args.out)
    report = {
        "repo_id": args.repo_id,
        "vocab_size": tok.vocab_size,
        "scale": tok.scale,
        "held_out": roundtrip_figures(tok, test_chunks),
        "fitted": roundtrip_figures(tok, fit_chunks),
    }
    (args.out / "fit_report.json").write_text(json.dumps(report, indent=2) + "\n")
    for part in ("held_out", "fitted"):
        r = report[part]
        print(
            f"{part:>8}: {r['chunks']} chunks, {r['tokens_per_chunk_mean']} tokens per chunk (p95 "
            f"{r['tokens_per_chunk_p95']}, max {r['tokens_per_chunk_max']}) for {r['codes_per_chunk']} codes; "
            f"round-trip |error| mean {r['abs_error_mean']:.4f}, p99 {r['abs_error_p99']:.4f}, max "
            f"{r['abs_error_max']:.4f} (normalised [-1, 1]); {r['decode_failures']} failed decodes"
        )
    print(f"saved to {args.out}")
    return report


if __name__ == "__main__":
    main()
