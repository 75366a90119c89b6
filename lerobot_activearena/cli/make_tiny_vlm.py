"""`activearena-make-tiny-vlm OUTDIR`: write a tiny random Qwen3-VL (model, tokenizer, image
processor) that ``--policy.vlm_path=OUTDIR`` loads exactly like ``Qwen/Qwen3-VL-2B-Instruct``;
for smoke runs, tests and docs on machines without the real weights."""

from __future__ import annotations

import argparse
from pathlib import Path


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    p.add_argument("out_dir", type=Path)
    p.add_argument("--hidden", type=int, default=64, help="text and vision width")
    p.add_argument("--layers", type=int, default=2, help="text decoder layers")
    p.add_argument(
        "--patch",
        type=int,
        default=16,
        help="vision patch side in pixels (tiny only); 32 with --policy.image_max_pixels=49152 reads "
        "192 x 256 images as 12 tokens each",
    )
    p.add_argument("--vision-hidden", type=int, help="vision tower width (tiny only; default: --hidden)")
    p.add_argument("--vision-depth", type=int, default=2, help="vision tower blocks (tiny only)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument(
        "--architecture",
        choices=["tiny", "qwen3-vl-2b"],
        default="tiny",
        help="qwen3-vl-2b: the real 2B model's dimensions with random weights (4.3 GB), for memory and "
        "latency figures without the weights",
    )
    p.add_argument("--overwrite", action="store_true")
    args = p.parse_args(argv)
    if (args.out_dir / "config.json").exists() and not args.overwrite:
        p.error(f"{args.out_dir} already holds a model; pass --overwrite to replace it")
    if args.hidden % 4 or args.hidden < 32:
        p.error("--hidden must be a multiple of 4 and >= 32")
    if args.patch < 8 or args.patch % 8:
        p.error(f"--patch must be a multiple of 8 and >= 8, got {args.patch}")
    vision_hidden = args.hidden if args.vision_hidden is None else args.vision_hidden
    if args.patch != 16 and args.architecture != "tiny":
        p.error("--patch applies to the tiny architecture only (the 2B model has 16 px patches)")
    from ..policies.activearena_vla.tiny_vlm import make_tiny_vlm
    from ..tasks.registry import task_texts

    try:
        out = make_tiny_vlm(
            args.out_dir,
            hidden=args.hidden,
            layers=args.layers,
            seed=args.seed,
            architecture=args.architecture,
            texts=task_texts(),
            patch=args.patch,
            vision_hidden=vision_hidden,
            vision_depth=args.vision_depth,
        )
    except ValueError as e:  # a size the model cannot take (--vision-hidden / --vision-depth)
        p.error(str(e))
    n = sum(f.stat().st_size for f in out.iterdir())
    what = (
        f"tiny Qwen3-VL ({args.layers} layers, width {args.hidden}, {args.patch} px patches, "
        f"vision tower {args.vision_depth} blocks of width {vision_hidden})"
        if args.architecture == "tiny"
        else "random Qwen3-VL with the 2B model's dimensions (not pretrained)"
    )
    print(f"{out}: {what}, {n / 1e6:.1f} MB; use --policy.vlm_path={out}")


if __name__ == "__main__":
    main()
