"""Do a build's per-object annotations match its images? Draws head frames of one episode with every
object that ``visible_object_mask`` calls visible marked at its ``object_uv_norm`` point and named
(the sidecar's keys), so that a wrong label, a shifted frame or a swapped slot shows at a glance.

    python analysis/tasks/annotation_overlay.py --root outputs/datasets/cpu_count_left_200_p16_192 \\
        --episode 0 --every 16 --out /tmp/overlay.png
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np


def overlay_frames(root: Path, episode: int, every: int, camera: str = "observation.images.head"):
    """[(frame index, HxWx3 uint8 image, [(key, u px, v px), ...]), ...] every ``every``-th frame."""
    from lerobot.datasets.lerobot_dataset import LeRobotDataset

    ds = LeRobotDataset("local/overlay", root=root, episodes=[episode], video_backend="pyav")
    if "object_uv_norm" not in ds.features:
        raise SystemExit(f"{root} has no object_uv_norm column: rebuild it with activearena-build-dataset")
    side = json.loads((root / f"meta/activearena/sidecars/episode_{episode:06d}.json").read_text())
    keys = {o["index"]: o["key"] for o in side["objects"]}
    out = []
    for i in range(0, len(ds), every):
        item = ds[i]
        image = (item[camera].permute(1, 2, 0).numpy() * 255).astype(np.uint8)
        h, w = image.shape[:2]
        visible = item["visible_object_mask"].numpy()
        uv = item["object_uv_norm"].numpy().reshape(-1, 2)
        marks = [(keys.get(k, str(k)), uv[k, 0] * w, uv[k, 1] * h) for k in np.flatnonzero(visible == 1)]
        out.append((int(item["frame_index"]), image, marks))
    return out


def main(argv: list[str] | None = None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--root", type=Path, required=True, help="a full build (with its annotations)")
    p.add_argument("--episode", type=int, default=0)
    p.add_argument("--every", type=int, default=16, help="draw every n-th frame")
    p.add_argument("--out", type=Path, required=True, help="the PNG to write")
    args = p.parse_args(argv)
    frames = overlay_frames(args.root, args.episode, args.every)
    fig, axes = plt.subplots(1, len(frames), figsize=(3.2 * len(frames), 2.8), squeeze=False)
    for ax, (t, image, marks) in zip(axes[0], frames, strict=True):
        ax.imshow(image)
        for key, u, v in marks:
            ax.plot(u, v, "+", color="white", ms=9, mew=1.5)
            ax.text(u + 3, v - 3, key.replace("_block", ""), color="white", fontsize=6)
        ax.set_title(f"t={t}: {len(marks)} visible", fontsize=8)
        ax.axis("off")
    fig.suptitle(f"{args.root.name} episode {args.episode}: visible_object_mask at object_uv_norm")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(args.out)


if __name__ == "__main__":
    main()
