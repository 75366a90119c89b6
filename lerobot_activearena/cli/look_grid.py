"""`activearena-look-grid`: head-camera frames of a task's scenes, ID in the top rows and OOD below,
to see what the two splits change (materials, light, clutter) and that no view shows a void.

Each scene is shown at the home view and turned towards the side its hidden objects are on (torso
yaw +-0.9 rad), as the robot sees it at the paper's 512 x 384."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw
from tqdm import tqdm

from ..sim.scene import HEAD_HEIGHT, HEAD_WIDTH
from ..sim.simulator import ActiveArenaSim
from ..tasks import get_task
from ..tasks.sampling import sample_scene

TURN_RAD = 0.9


def scene_frames(task: str, seed: int, split: str, scale: float) -> list[np.ndarray]:
    """The home view and a turned view of one scene, resized by ``scale``."""
    scene = sample_scene(get_task(task), seed, split)
    sim = ActiveArenaSim(scene.model, scene.info)
    sim.reset()
    frames = [sim.render_head()]
    action = sim.home_action()
    action[16] = TURN_RAD if seed % 2 == 0 else -TURN_RAD
    for _ in range(25):
        sim.step(action)
    frames.append(sim.render_head())
    sim.close()
    size = (int(HEAD_WIDTH * scale), int(HEAD_HEIGHT * scale))
    return [np.asarray(Image.fromarray(f).resize(size, Image.BILINEAR)) for f in frames]


def look_grid(task: str, seeds: int, scale: float = 0.5) -> Image.Image:
    rows = []
    for split in ("id", "ood"):
        for seed in tqdm(range(seeds), desc=f"{task} {split}"):
            rows.append(
                (f"{split.upper()} seed {seed}", np.concatenate(scene_frames(task, seed, split, scale), 1))
            )
    sheet = Image.fromarray(np.concatenate([r for _, r in rows], 0))
    draw = ImageDraw.Draw(sheet)
    for k, (label, row) in enumerate(rows):
        y = k * row.shape[0]
        box = draw.textbbox((4, y + 2), label)
        draw.rectangle([0, y, box[2] + 4, box[3] + 2], fill=(0, 0, 0))
        draw.text((4, y + 2), label, fill=(255, 255, 255))
    return sheet


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--task", default="click_bell_rotate_view")
    p.add_argument("--seeds", type=int, default=3, help="scenes per split")
    p.add_argument("--scale", type=float, default=0.5, help="frame size relative to 512 x 384")
    p.add_argument("--out", type=Path, default=Path("outputs/look_grid.png"))
    args = p.parse_args(argv)
    if args.seeds < 1 or not 0 < args.scale <= 1:
        raise SystemExit("--seeds must be >= 1 and --scale in (0, 1]")
    sheet = look_grid(args.task, args.seeds, args.scale)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
