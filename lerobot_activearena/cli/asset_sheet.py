"""`activearena-asset-sheet`: render every asset category on the fan table in front of the head
camera and write a labelled contact sheet (PNG), to check by eye that objects read as what they are.

Each thumbnail is the head-camera image (512x384, the policy's view) cropped around the object;
``--zoom 2`` crops half as much and enlarges it (nearest neighbour, so pixels stay honest)."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw
from tqdm import tqdm

from ..sim.assets import ASSETS, categories
from ..sim.scene import HEAD_HEIGHT, HEAD_WIDTH, SceneBuilder
from ..sim.simulator import ActiveArenaSim

THUMB = (256, 192)


def render_category(
    category: str, seed: int = 0, distance: float = 0.5, zoom: float = 1.0, randomize: bool = True
) -> np.ndarray:
    """Head-camera view of one object ``distance`` m straight ahead, cropped (THUMB / zoom) around
    its projected bounding box and resized to THUMB."""
    b = SceneBuilder()
    rng = np.random.default_rng(seed) if randomize else None
    b.add_object(category, f"sample_{category}", distance, 90.0, yaw=math.radians(90.0 + 35.0), rng=rng)
    model, info = b.compile()
    sim = ActiveArenaSim(model, info)
    for _ in range(3):
        sim.step(sim.home_action())
    img = sim.render_head()
    uv = sim.visibility().uv_norm[0]
    sim.close()
    u, v = (
        (uv * (HEAD_WIDTH, HEAD_HEIGHT)).astype(int)
        if uv[0] >= 0
        else (HEAD_WIDTH // 2, HEAD_HEIGHT * 2 // 5)
    )
    w, h = int(THUMB[0] / zoom), int(THUMB[1] / zoom)
    x0 = int(np.clip(u - w // 2, 0, HEAD_WIDTH - w))
    y0 = int(np.clip(v - h // 2, 0, HEAD_HEIGHT - h))
    crop = Image.fromarray(img[y0 : y0 + h, x0 : x0 + w])
    return np.asarray(crop.resize(THUMB, Image.NEAREST))


def contact_sheet(cats: list[str], columns: int = 8, **render_kw) -> Image.Image:
    cols = max(1, min(columns, len(cats)))
    rows = math.ceil(len(cats) / cols)
    sheet = Image.new("RGB", (cols * THUMB[0], rows * THUMB[1]), (0, 0, 0))
    draw = ImageDraw.Draw(sheet)
    for k, cat in enumerate(tqdm(cats, desc="assets")):
        x, y = (k % cols) * THUMB[0], (k // cols) * THUMB[1]
        sheet.paste(Image.fromarray(render_category(cat, **render_kw)), (x, y))
        label = f"{cat} ({ASSETS[cat].role})"
        box = draw.textbbox((x + 4, y + 2), label)
        draw.rectangle([x, y, box[2] + 4, box[3] + 2], fill=(0, 0, 0))
        draw.text((x + 4, y + 2), label, fill=(255, 255, 255))
    return sheet


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument(
        "--categories", default="all", help="comma list of categories, or 'all', 'task', 'distractor'"
    )
    p.add_argument("--out", type=Path, default=Path("outputs/assets.png"))
    p.add_argument("--columns", type=int, default=8)
    p.add_argument("--seed", type=int, default=0, help="attribute randomisation seed")
    p.add_argument(
        "--default-look", action="store_true", help="builder defaults instead of randomised attributes"
    )
    p.add_argument(
        "--distance", type=float, default=0.5, help="object distance from the robot base (0.35-1.0 m)"
    )
    p.add_argument("--zoom", type=float, default=1.0, help="enlarge the crop around each object (>= 1)")
    args = p.parse_args(argv)
    if args.categories in ("all", "task", "distractor"):
        cats = categories(None if args.categories == "all" else args.categories)
    else:
        cats = [c.strip() for c in args.categories.split(",") if c.strip()]
        unknown = [c for c in cats if c not in ASSETS]
        if unknown:
            raise SystemExit(f"unknown categories {unknown}; known: {sorted(ASSETS)}")
    if args.zoom < 1.0:
        raise SystemExit("--zoom must be >= 1")
    sheet = contact_sheet(
        cats,
        args.columns,
        seed=args.seed,
        distance=args.distance,
        zoom=args.zoom,
        randomize=not args.default_look,
    )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out)
    print(f"wrote {args.out} ({len(cats)} categories)")


if __name__ == "__main__":
    main()
