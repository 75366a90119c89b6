"""`activearena-ground-vision VLM_DIR --root BUILD --out OUT_DIR`: fit a from-scratch Qwen3-VL's vision
tower to where the focus object is in a build's head frames (which merged token holds it, or none), and
save the grounded model for ``--policy.vlm_path=OUT_DIR``.

A tiny backbone from ``activearena-make-tiny-vlm`` starts without the visual grounding Qwen3-VL-2B brings
from pretraining; this gives it that from the build's per-frame annotations before policy training.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from .args import int_ranges


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    p.add_argument(
        "vlm_dir", type=Path, help="the Qwen3-VL to ground (a folder from activearena-make-tiny-vlm)"
    )
    p.add_argument("--root", type=Path, required=True, help="a full build (activearena-build-dataset --root)")
    p.add_argument("--out", type=Path, required=True, help="where the grounded model is written")
    p.add_argument("--epochs", type=int, default=5)
    p.add_argument("--batch-size", type=int, default=64)
    p.add_argument("--lr", type=float, default=3e-4)
    p.add_argument(
        "--image-max-pixels",
        type=int,
        default=12288,
        help="as the policy's --policy.image_max_pixels (12,288: 96 x 128 images at their size)",
    )
    p.add_argument("--val-every", type=int, default=10, help="hold out every N-th episode and score it")
    p.add_argument(
        "--episodes",
        type=int_ranges,
        default=None,
        help="ground on these episodes of the build only, e.g. 0-199 (default: all). The frames are held "
        "decoded in memory (192 x 256: 147 kB each), so a large build needs a subset",
    )
    p.add_argument("--seed", type=int, default=0)
    p.add_argument(
        "--point-weight",
        type=float,
        default=0.0,
        help="weight of also fitting where in its token the object lies (0: the token only)",
    )
    p.add_argument(
        "--search-weight",
        type=float,
        default=0.0,
        help="weight of also fitting which tokens hold the task's search targets in view and how many "
        "there are (a count task's blocks to count; 0: the focus object only)",
    )
    p.add_argument(
        "--identity-weight",
        type=float,
        default=0.0,
        help="weight of also fitting which objects each token holds by their look (the sidecar's names "
        "without instance numbers: 'button 2', 'green block'); a frozen tower needs it to tell the count "
        "task's buttons apart (0: off)",
    )
    p.add_argument(
        "--reading-window",
        type=int,
        default=0,
        help="with --identity-weight: within this many frames of each expert reading (an inspection task's "
        "hidden face shown to the camera) the inspected object's class is what it shows ('gray block "
        "showing green'), so a frozen tower keeps the reading for the memory (0: off)",
    )
    p.add_argument(
        "--jitter",
        action="store_true",
        help="colour-jitter the training frames (act_cpu_jitter's brightness, contrast, saturation and hue)",
    )
    p.add_argument(
        "--random-conv",
        action="store_true",
        help="pass half the training frames through a random convolution (RandConv: new colours and "
        "textures, the same shapes), after --jitter if both",
    )
    p.add_argument(
        "--eval-root",
        type=Path,
        default=None,
        help="another full build (an OOD one: activearena-build-dataset --split ood) scored whole after each epoch",
    )
    p.add_argument("--overwrite", action="store_true")
    args = p.parse_args(argv)
    if not (args.vlm_dir / "config.json").exists():
        p.error(f"{args.vlm_dir} holds no model; make one with `activearena-make-tiny-vlm {args.vlm_dir}`")
    if not (args.root / "meta/info.json").exists():
        p.error(f"{args.root} is not a LeRobot dataset; build one with activearena-build-dataset")
    if args.eval_root is not None and not (args.eval_root / "meta/info.json").exists():
        p.error(
            f"--eval-root {args.eval_root} is not a LeRobot dataset; build one with activearena-build-dataset"
        )
    if args.out.resolve() == args.vlm_dir.resolve():
        p.error("--out must differ from VLM_DIR: the ungrounded model is kept")
    if (args.out / "config.json").exists() and not args.overwrite:
        p.error(f"{args.out} already holds a model; pass --overwrite to replace it")
    if (
        args.epochs < 1
        or args.batch_size < 1
        or args.val_every < 2
        or min(args.point_weight, args.search_weight, args.identity_weight) < 0
        or args.reading_window < 0
    ):
        p.error(
            "--epochs and --batch-size must be >= 1, --val-every >= 2, and the --*-weight options and "
            "--reading-window >= 0"
        )
    from ..policies.activearena_vla.vision_grounding import ground_vision_tower

    try:
        report = ground_vision_tower(
            args.vlm_dir,
            args.root,
            args.out,
            epochs=args.epochs,
            batch_size=args.batch_size,
            lr=args.lr,
            max_pixels=args.image_max_pixels,
            val_every=args.val_every,
            seed=args.seed,
            point_weight=args.point_weight,
            search_weight=args.search_weight,
            identity_weight=args.identity_weight,
            reading_window=args.reading_window,
            jitter=args.jitter,
            random_conv=args.random_conv,
            eval_root=args.eval_root,
            episodes=args.episodes,
        )
    except ValueError as e:  # a build without the annotations
        p.error(str(e))
    last = report["history"][-1]
    point = (
        f", point {last['median_point_error_px']:.1f} px from the object (token centre "
        f"{last['median_centre_error_px']:.1f} px)"
        if "median_point_error_px" in last
        else ""
    )
    search = (
        f"; search targets in view counted right {last['search_count_accuracy']:.1%} (the most common "
        f"count {last['search_count_majority']:.1%}), their tokens at precision "
        f"{last['search_token_precision']:.1%} / recall {last['search_token_recall']:.1%}"
        if "search_count_accuracy" in last
        else ""
    )
    identity = (
        f"; objects named right in {last['identity_accuracy']:.1%} of the tokens holding one kind (the most "
        f"common kind {last['identity_majority']:.1%})"
        if "identity_accuracy" in last
        else ""
    )
    if "reading_accuracy" in last:
        identity += (
            f"; readings named right in {last['reading_accuracy']:.1%} of the tokens showing one (the most "
            f"common {last['reading_majority']:.1%})"
        )
    elsewhere = (
        f"; {args.eval_root}: in view or not {last['eval_in_view_accuracy']:.1%}, token "
        f"{last['eval_token_accuracy_where_visible']:.1%} where visible ({last['eval_frames']} frames)"
        if args.eval_root is not None
        else ""
    )
    print(
        f"{args.out}: held-out episodes, in view or not {last['in_view_accuracy']:.1%}, token "
        f"{last['token_accuracy_where_visible']:.1%} where visible ({last['frames']} frames){point}{search}{identity}{elsewhere}; "
        f"use --policy.vlm_path={args.out}"
    )


if __name__ == "__main__":
    main()
