"""`activearena-cache-vision VLM_DIR --root BUILD --repo-id ID --out FILE`: a frozen vision tower's features
of every head frame of a build, for training with ``--policy.freeze_vision=true --policy.vision_cache=FILE``.

The chunk memory's 12 history frames then cost neither video decoding nor the tower at each training step;
the table is checked against the policy's tower (a fingerprint of its weights) and image size.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    p.add_argument("vlm_dir", help="the backbone, as --policy.vlm_path (its vision tower stays frozen)")
    p.add_argument("--root", type=Path, required=True, help="the training build (--dataset.root)")
    p.add_argument("--repo-id", required=True, help="its repo id (--dataset.repo_id)")
    p.add_argument("--out", type=Path, required=True, help="the table to write (.safetensors)")
    p.add_argument(
        "--image-max-pixels",
        type=int,
        default=12288,
        help="as the policy's --policy.image_max_pixels (12,288: 96 x 128 images at their size)",
    )
    p.add_argument("--batch-size", type=int, default=64)
    p.add_argument("--overwrite", action="store_true")
    args = p.parse_args(argv)
    if not (args.root / "meta/info.json").exists():
        p.error(f"{args.root} is not a LeRobot dataset; build one with activearena-build-dataset")
    if args.out.exists() and not args.overwrite:
        p.error(f"{args.out} exists; pass --overwrite to replace it")
    if args.batch_size < 1:
        p.error("--batch-size must be >= 1")
    from ..policies.activearena_vla.vision_cache import compute_vision_cache

    meta = compute_vision_cache(
        args.vlm_dir, args.root, args.repo_id, args.image_max_pixels, args.out, batch_size=args.batch_size
    )
    print(json.dumps(meta, indent=1))
    print(
        f"{args.out}: {meta['frames']} frames; train with --policy.freeze_vision=true --policy.vision_cache={args.out}"
    )


if __name__ == "__main__":
    main()
