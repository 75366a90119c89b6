"""Does a trained ACT policy decide a search turn from the image or from the state? A swap probe on a
built rotate-view dataset (e.g. the bell's, built with ``--search-overshoot``):

    python analysis/policies/search_decision_probe.py --checkpoint outputs/train/.../pretrained_model \\
        --root outputs/datasets/cpu_click_bell_200_recovery --frames docs/img/bell_decision_frames.png

Episodes are split by what the expert does at the first sector's end: ``found`` (it ends there, the
object on that side) and ``recovery`` (it sweeps to the torso's end, then turns back). At the first
frame whose torso yaw passes each probe angle, the policy predicts a chunk from the head image of one
kind and the state of the other (and unswapped); the script prints the mean torso change over the
chunk per pairing. If the image decides, the change follows the image column.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pandas as pd
import torch

TORSO, HEAD_PITCH = 16, 17  # indices in observation.state / action


def episode_kinds(frame: pd.DataFrame) -> dict[int, str]:
    kinds = {}
    for ep, g in frame.groupby("episode_index"):
        torso = np.stack(g["action"].values)[:, TORSO]
        if torso.min() < -1.1 and torso[-1] > 0:
            kinds[ep] = "recovery"
        elif torso[-1] < -1.1:
            kinds[ep] = "found"
    return kinds


def first_index_past(frame: pd.DataFrame, ep: int, angle: float) -> int | None:
    g = frame[frame["episode_index"] == ep]
    torso = np.stack(g["observation.state"].values)[:, TORSO]
    hits = np.where(torso <= angle)[0]
    return int(g["index"].values[hits[0]]) if len(hits) else None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--checkpoint", required=True, help="a pretrained_model folder of an ACT run")
    ap.add_argument("--root", required=True, help="a dataset activearena-build-dataset wrote")
    ap.add_argument("--angles", default="-1.0,-1.15", help="torso yaw probe angles (rad), comma separated")
    ap.add_argument("--pairs", type=int, default=12, help="episode pairs per angle")
    ap.add_argument("--frames", type=Path, help="also save the head frames at the last angle as a PNG")
    args = ap.parse_args()

    from lerobot.datasets.lerobot_dataset import LeRobotDataset
    from lerobot.policies.act.modeling_act import ACTPolicy
    from lerobot.policies.factory import make_pre_post_processors

    root = Path(args.root)
    dataset = LeRobotDataset(f"local/{root.name}", root=root)
    frame = pd.concat(pd.read_parquet(f) for f in sorted(root.glob("data/*/*.parquet")))
    kinds = episode_kinds(frame)
    if not any(k == "recovery" for k in kinds.values()):
        raise SystemExit(f"{root} has no recovery sweeps: build it with --search-overshoot > 0")

    policy = ACTPolicy.from_pretrained(args.checkpoint)
    policy.config.device = "cpu"
    policy.to("cpu").eval()
    cpu = {"device_processor": {"device": "cpu"}}
    pre, post = make_pre_post_processors(
        policy.config,
        pretrained_path=args.checkpoint,
        preprocessor_overrides=cpu,
        postprocessor_overrides=cpu,
    )

    def torso_change(image, state) -> float:
        batch = pre({"observation.images.head": image[None], "observation.state": state[None], "task": [""]})
        with torch.no_grad():
            chunk = post(policy.predict_action_chunk(batch))
        return float(chunk[0, -1, TORSO] - state[TORSO])

    shown = []
    for angle in (float(a) for a in args.angles.split(",")):
        picks = {k: [] for k in ("found", "recovery")}
        for ep, kind in sorted(kinds.items()):
            index = first_index_past(frame, ep, angle)
            if index is not None and len(picks[kind]) < args.pairs:
                picks[kind].append(index)
        rows: dict[str, list[float]] = {}
        for fi, ri in zip(picks["found"], picks["recovery"], strict=False):
            found, recovery = dataset[fi], dataset[ri]
            for image_kind, image in (("found", found), ("recovery", recovery)):
                for state_kind, state in (("found", found), ("recovery", recovery)):
                    change = torso_change(image["observation.images.head"], state["observation.state"])
                    rows.setdefault(f"image {image_kind:8s} state {state_kind:8s}", []).append(change)
        print(f"torso at {angle:+.2f} rad: torso change over the chunk (rad), {len(picks['found'])} pairs")
        for name, changes in rows.items():
            print(f"  {name}  {np.mean(changes):+.3f}  (sd {np.std(changes):.3f})")
        shown = [dataset[i]["observation.images.head"] for i in picks["found"][:4] + picks["recovery"][:4]]

    if args.frames and shown:
        from PIL import Image

        tiles = [Image.fromarray((im.permute(1, 2, 0).numpy() * 255).astype(np.uint8)) for im in shown]
        w, h = tiles[0].size
        sheet = Image.new("RGB", (4 * w + 15, 2 * h + 5), "white")
        for k, tile in enumerate(tiles):
            sheet.paste(tile, ((k % 4) * (w + 5), (k // 4) * (h + 5)))
        args.frames.parent.mkdir(parents=True, exist_ok=True)
        sheet.resize((sheet.width * 2, sheet.height * 2), Image.NEAREST).save(args.frames)
        print(f"frames (top: found, bottom: recovery) -> {args.frames}")


if __name__ == "__main__":
    main()
