"""The numbered buttons of the count tasks as the head camera sees them at three image sizes.

Runs the expert on one count_target_press_button scene at 96 x 128 (the CPU recipe), 192 x 256 (about
the paper's 50,176-pixel model input) and 384 x 512 (the rendered head image) and writes one frame of
the press approach from each, scaled to the same size, side by side. At 96 x 128 a digit label is about
4 pixels wide and the three numbers are not told apart; at 192 x 256 they are legible.

    python analysis/tasks/button_digits_by_resolution.py --out docs/img/button_digits_by_resolution.png
"""

from __future__ import annotations

import argparse

import lerobot_activearena  # noqa: F401  (first: pins numpy's BLAS kernels before numpy loads)

# isort: split
import numpy as np
from PIL import Image, ImageDraw

SIZES = ((96, 128), (192, 256), (384, 512))


def label_widths(sim) -> list[float]:
    """The projected width (px) of each visible button's digit label, in the current head image."""
    import mujoco

    from lerobot_activearena.sim.camera import project

    cam = sim.head_camera()
    widths = []
    for n in (1, 2, 3):
        g = mujoco.mj_name2id(sim.model, mujoco.mjtObj.mjOBJ_GEOM, f"button_{n}_label")
        half = sim.model.geom_size[g][:2]
        rot = sim.data.geom_xmat[g].reshape(3, 3)
        corners = sim.data.geom_xpos[g] + np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]) * half @ rot[:, :2].T
        px, depth = project(corners, cam["intrinsic_cv"], cam["extrinsic_cv"])
        inside = (depth > 0).all() and (px >= 0).all() and (px[:, 0] < sim.image_width).all()
        inside = inside and (px[:, 1] < sim.image_height).all()
        if inside:
            a, b = px[1] - px[0], px[3] - px[0]
            widths.append(float(np.sqrt(abs(a[0] * b[1] - a[1] * b[0]))))
    return widths


def press_frame(
    task: str, seed: int, size: tuple[int, int], before_end: int
) -> tuple[np.ndarray, list[float]]:
    """The head image ``before_end`` frames before the expert's last, and its labels' widths (px)."""
    from lerobot_activearena.episodes.rollout import run_expert_episode

    frames = []
    result = run_expert_episode(
        task,
        seed,
        image_size=size,
        on_frame=lambda t, sim, a, act: frames.append((sim.render_head(), label_widths(sim))),
    )
    if not result.success:
        raise RuntimeError(f"the expert failed {task} seed {seed}; pick another --seed")
    return frames[max(0, len(frames) - 1 - before_end)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="count_target_press_button")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--before-end", type=int, default=30, help="frames before the episode's last")
    parser.add_argument("--out", default="button_digits_by_resolution.png")
    args = parser.parse_args()
    tiles = []
    for h, w in SIZES:
        frame, widths = press_frame(args.task, args.seed, (h, w), args.before_end)
        img = Image.fromarray(frame)
        img = img.resize((512, 384), Image.NEAREST)
        ImageDraw.Draw(img).text(
            (8, 8), f"{h} x {w}", fill=(255, 255, 255), stroke_width=2, stroke_fill=(0, 0, 0)
        )
        tiles.append(np.asarray(img))
        print(
            f"{h} x {w}: the visible digit labels span "
            + ", ".join(f"{x:.1f}" for x in widths)
            + " px (sqrt of area)"
        )
    Image.fromarray(np.concatenate(tiles, 1)).save(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
