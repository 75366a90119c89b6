"""A memory checkpoint that starts as a memory-free one: the memory-free checkpoint's weights in the
layout of a checkpoint of the memory preset (its config, processors and frozen memory tower), to
continue with ``lerobot-train --policy.pretrained_path=OUT --policy.memory_readers=span``.

    python analysis/policies/warm_start_memory.py outputs/train/inspection_no_0/checkpoints/008000/pretrained_model \\
        --layout outputs/train/inspection_action_12/checkpoints/008000/pretrained_model --out outputs/warm/no_0_as_action_12

Every weight the two share comes from the memory-free checkpoint; the memory tower (a frozen copy of
the backbone's tower as loaded, the same in every checkpoint of the preset) from ``--layout``. The
state encoder's frame embedding grows from the memory-free one row (the current frame) to the
memory preset's slots: the current frame's slot keeps that row and every memory slot starts as a copy
of it. Under ``memory_readers=span`` the prompt, the current frame and the action queries do not read
a memory frame, so the continued policy starts acting as the memory-free one does (its tokens' places
shift by the memory's length) while its think span learns to read the memory.
"""

from __future__ import annotations

import argparse
import json
import shutil
from pathlib import Path

FRAME = "state_encoder.frame.weight"
TOWER = "memory_tower."


def warm_start(memory_free: Path, layout: Path, out: Path) -> dict:
    """Writes ``out`` (``layout``'s files, the merged weights); returns what came from where."""
    from safetensors.torch import load_file, save_file

    free = json.loads((memory_free / "config.json").read_text())
    target = json.loads((layout / "config.json").read_text())
    if free.get("history", 0) != 0:
        raise SystemExit(
            f"{memory_free} has a memory (history {free['history']}): give a memory-free checkpoint"
        )
    if target.get("history", 0) == 0:
        raise SystemExit(f"--layout {layout} has no memory: give a checkpoint of the memory preset")
    if free["vlm_path"] != target["vlm_path"] or free["type"] != target["type"]:
        raise SystemExit(
            f"the two checkpoints are not one preset with and without memory: {free['type']} on "
            f"{free['vlm_path']} vs {target['type']} on {target['vlm_path']}"
        )
    if out.exists() and any(out.iterdir()):
        raise SystemExit(f"{out} is not empty: give a new folder")
    weights, shape = load_file(memory_free / "model.safetensors"), load_file(layout / "model.safetensors")
    only_free = sorted(set(weights) - set(shape))
    only_target = sorted(k for k in set(shape) - set(weights) if not k.startswith(TOWER))
    if only_free or only_target:
        raise SystemExit(f"weights the layouts do not share: {only_free[:3]} / {only_target[:3]}")
    merged = {}
    for key, value in shape.items():
        if key.startswith(TOWER):
            merged[key] = value
        elif key == FRAME:
            merged[key] = weights[key][-1:].expand_as(value).clone()  # the current frame's row everywhere
        elif weights[key].shape != value.shape:
            raise SystemExit(f"{key}: {tuple(weights[key].shape)} vs {tuple(value.shape)}")
        else:
            merged[key] = weights[key]
    out.mkdir(parents=True, exist_ok=True)
    for f in layout.iterdir():
        if f.name != "model.safetensors" and f.is_file():
            shutil.copy2(f, out / f.name)
    save_file({k: v.contiguous() for k, v in merged.items()}, out / "model.safetensors")
    return {
        "memory_free": sum(not k.startswith(TOWER) for k in merged),
        "layout": sum(k.startswith(TOWER) for k in merged),
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("memory_free", type=Path, help="the memory-free checkpoint's pretrained_model folder")
    p.add_argument(
        "--layout", type=Path, required=True, help="a pretrained_model folder of the memory preset"
    )
    p.add_argument("--out", type=Path, required=True, help="a new folder for the merged checkpoint")
    args = p.parse_args()
    counts = warm_start(args.memory_free, args.layout, args.out)
    print(
        f"{args.out}: {counts['memory_free']} tensors from {args.memory_free}, "
        f"{counts['layout']} (the memory tower) from {args.layout}"
    )


if __name__ == "__main__":
    main()
