"""Where the sampler puts things: azimuth / radius of every task object (by role) and of the clutter,
per task, over many seeds, with the head camera's home view drawn in.

    python analysis/tasks/placement_distribution.py --seeds 100 --splits id,ood --out docs/placement.png

Prints per task and role the sampled radius and azimuth ranges and the share on the robot's left
(azimuth > 90 deg); saves a polar scatter plot, one panel per task.
"""

from __future__ import annotations

import argparse
import collections
import math
import os
from pathlib import Path

import lerobot_activearena  # noqa: F401  (first: pins numpy's BLAS kernels before numpy loads)

# isort: split
import numpy as np


def home_view_outline(radii: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Leftmost / rightmost visible azimuth (deg) at each radius, at the tabletop."""
    from lerobot_activearena.tasks.draft import in_home_view

    lo, hi = [], []
    angles = np.arange(20.0, 160.01, 0.5)
    for r in radii:
        vis = [
            a
            for a in angles
            if in_home_view(
                (r * math.cos(math.radians(a)), r * math.sin(math.radians(a))), 0.0, heights=(0.0,)
            )
        ]
        lo.append(min(vis) if vis else np.nan)
        hi.append(max(vis) if vis else np.nan)
    return np.array(lo), np.array(hi)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--tasks", default="all")
    p.add_argument("--splits", default="id,ood")
    p.add_argument("--seeds", type=int, default=100)
    p.add_argument("--out", type=Path, default=Path("outputs/placement.png"))
    args = p.parse_args()
    os.environ.setdefault("MUJOCO_GL", "egl")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from tqdm import tqdm

    from lerobot_activearena.tasks import get_task, task_names
    from lerobot_activearena.tasks.sampling import sample_scene

    names = task_names(args.tasks)
    splits = args.splits.split(",")
    data: dict[str, dict[str, list]] = {n: collections.defaultdict(list) for n in names}
    for name in names:
        task = get_task(name)
        for split in splits:
            for seed in tqdm(range(args.seeds), desc=f"{name} {split}", leave=False):
                scene = sample_scene(task, seed, split)
                for q in scene.params["placements"]:
                    role = q["category"] + (" (hidden at home)" if q["hidden"] else "")
                    data[name][role].append((q["r"], q["angle"]))
                for o in scene.info.clutter:
                    x, y = scene.model.body(o.body).pos[:2]
                    data[name]["clutter"].append((math.hypot(x, y), math.degrees(math.atan2(y, x))))
    print("| task | role | samples | radius (m) | azimuth (deg) | left of heading |")
    print("|---|---|---|---|---|---|")
    for name in names:
        for role, pts in sorted(data[name].items()):
            a = np.array(pts)
            print(
                f"| {name} | {role} | {len(a)} | {a[:, 0].min():.2f}-{a[:, 0].max():.2f} | "
                f"{a[:, 1].min():.0f}-{a[:, 1].max():.0f} | {100 * np.mean(a[:, 1] > 90):.0f}% |"
            )

    radii = np.linspace(0.3, 1.08, 40)
    lo, hi = home_view_outline(radii)
    cols = min(3, len(names))
    rows = math.ceil(len(names) / cols)
    fig = plt.figure(figsize=(5.2 * cols, 3.6 * rows))
    for k, name in enumerate(names):
        ax = fig.add_subplot(rows, cols, k + 1, projection="polar")
        ax.set_thetamin(0)
        ax.set_thetamax(180)
        ax.set_rlim(0, 1.1)
        ax.set_rticks([0.3, 0.6, 0.9])
        ax.tick_params(labelsize=7)
        ax.fill_betweenx(radii, np.radians(lo), np.radians(hi), color="#cfe8ff", alpha=0.6, label="home view")
        for role, pts in sorted(data[name].items(), key=lambda kv: kv[0] == "clutter", reverse=True):
            a = np.array(pts)
            style = {"s": 4, "alpha": 0.35, "color": "0.6"} if role == "clutter" else {"s": 7, "alpha": 0.7}
            ax.scatter(
                np.radians(a[:, 1]), a[:, 0], label=role, marker="x" if "hidden" in role else "o", **style
            )
        ax.set_title(name, fontsize=9)
        ax.legend(fontsize=6, loc="lower left", bbox_to_anchor=(-0.05, -0.32), ncol=2, frameon=False)
    fig.suptitle(
        f"sampled placements ({args.seeds} seeds x {'/'.join(splits)}); 90 deg = torso heading at home",
        fontsize=10,
    )
    fig.tight_layout()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
