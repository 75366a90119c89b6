"""`activearena-asset-sheet`: render every asset category on the fan table in front of the head
camera and write a labelled contact sheet (PNG), to check by eye that objects read as what they are."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw
from tqdm import tqdm

from ..sim.assets import ASSETS, categories
from ..sim.scene import SceneBuilder
from ..sim.simulator import ActiveArenaSim

THUMB = (256, 192)


def render_category(category: str, seed: int = 0) -> np.ndarray:
    """Head-camera view (cropped around the object) of one object 0.5 m in front of the robot."""
    b = SceneBuilder()
    rng = np.random.default_rng(seed)
    b.add_object(category, f"sample_{category}", 0.5, 90.0, yaw=math.radians(90.0 + 35.0), rng=rng)
    model, info = b.compile()
    sim = ActiveArenaSim(model, info)
    for _ in range(3):
        sim.step(sim.home_action())
    img = sim.render_head()
    sim.close()
    u, v = 256, 150  # where 0.5 m ahead lands in the image
    crop = img[max(0, v - 96): v + 96, u - 128: u + 128]
    return crop


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--categories", default="all", help="comma list of categories, or 'all', 'task', 'distractor'")
    p.add_argument("--out", type=Path, default=Path("outputs/assets.png"))
    p.add_argument("--columns", type=int, default=8)
    args = p.parse_args(argv)
    if args.categories in ("all", "task", "distractor"):
        cats = categories(None if args.categories == "all" else args.categories)
    else:
        cats = [c.strip() for c in args.categories.split(",") if c.strip()]
        unknown = [c for c in cats if c not in ASSETS]
        if unknown:
            raise SystemExit(f"unknown categories {unknown}; known: {sorted(ASSETS)}")
    cols = min(args.columns, len(cats))
    rows = math.ceil(len(cats) / cols)
    sheet = Image.new("RGB", (cols * THUMB[0], rows * THUMB[1]), (0, 0, 0))
    draw = ImageDraw.Draw(sheet)
    for k, cat in enumerate(tqdm(cats, desc="assets")):
        x, y = (k % cols) * THUMB[0], (k // cols) * THUMB[1]
        sheet.paste(Image.fromarray(render_category(cat)).resize(THUMB), (x, y))
        label = f"{cat} ({ASSETS[cat].role})"
        draw.rectangle([x, y, x + 8 + 7 * len(label), y + 14], fill=(0, 0, 0))
        draw.text((x + 4, y + 2), label, fill=(255, 255, 255))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out)
    print(f"wrote {args.out} ({len(cats)} categories)")


if __name__ == "__main__":
    main()
