"""Can a frozen vision tower's features tell the count task's buttons apart? For each vision cache
(`activearena-cache-vision`) of a count build, a linear probe learns the number of the button in a
merged token (the token under the button's ``object_uv_norm`` point; tokens holding two buttons are
skipped) on episodes 0-159 and is scored on the rest (all frames, and the press subtask's, where the
view is on the buttons). A frozen policy can only press the button of
the count if the button's number is in these features; chance is about 1/3.

    python analysis/policies/button_digit_probe.py --root outputs/datasets/cpu_count_left_200_p16_192 \\
        outputs/vision_cache/cpu_count_left_200_p16_192_grounded_search.safetensors CACHE...
"""

from __future__ import annotations

import argparse
import glob
import json
from pathlib import Path

import numpy as np
import torch


def button_tokens(
    root: Path, rows: int, cols: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(frame row in dataset index order, token, button number, episode, subtask) for every visible
    button alone in its token."""
    import pandas as pd

    data = pd.concat(pd.read_parquet(f) for f in sorted(glob.glob(f"{root}/data/*/*.parquet")))
    data = data.sort_values("index").reset_index(drop=True)
    slots = {}
    for path in sorted((root / "meta/activearena/sidecars").glob("episode_*.json")):
        side = json.loads(path.read_text())
        slots[int(path.stem.split("_")[1])] = {
            o["index"]: int(o["key"].split("_")[1]) for o in side["objects"] if o["category"] == "button"
        }
    visible = np.stack(data["visible_object_mask"].to_numpy()) == 1
    uv = np.stack(data["object_uv_norm"].to_numpy()).reshape(len(data), -1, 2)
    episodes, subtasks = data["episode_index"].to_numpy(), data["subtask_index"].to_numpy()
    out = []
    for i, ep in enumerate(episodes):
        cells = {}
        for slot, number in slots[int(ep)].items():
            if visible[i, slot]:
                u, v = uv[i, slot]
                cell = min(int(v * rows), rows - 1) * cols + min(int(u * cols), cols - 1)
                cells.setdefault(cell, []).append(number)
        out += [(i, cell, nums[0], ep, subtasks[i]) for cell, nums in cells.items() if len(nums) == 1]
    return tuple(np.array(c) for c in zip(*out, strict=True))


def linear_probe(x: torch.Tensor, y: torch.Tensor, train: torch.Tensor, steps: int = 400) -> torch.Tensor:
    """A softmax regression fitted on the ``train`` rows; the predicted class of every row."""
    mean, std = x[train].mean(0), x[train].std(0) + 1e-6
    x = (x - mean) / std
    torch.manual_seed(0)
    head = torch.nn.Linear(x.shape[1], int(y.max()) + 1)
    opt = torch.optim.Adam(head.parameters(), lr=1e-2, weight_decay=1e-4)
    rows = torch.nonzero(train)[:, 0]
    for _ in range(steps):
        batch = rows[torch.randint(0, len(rows), (1024,))]
        opt.zero_grad()
        torch.nn.functional.cross_entropy(head(x[batch]), y[batch]).backward()
        opt.step()
    with torch.no_grad():
        return head(x).argmax(1)


def main(argv: list[str] | None = None) -> None:
    from safetensors import safe_open

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("caches", nargs="+", type=Path, help="vision caches of the build")
    p.add_argument("--root", type=Path, required=True, help="the full build (with object_uv_norm)")
    p.add_argument("--heldout-from", type=int, default=160, help="episodes from this one are held out")
    args = p.parse_args(argv)
    print(
        "| vision cache | features | train accuracy | held-out accuracy | held out, press subtask | samples |"
    )
    print("|---|---|---|---|---|---|")
    for cache in args.caches:
        f = safe_open(str(cache), "pt")
        _, rows, cols = json.loads(f.metadata()["meta"])["grid"]
        rows, cols = rows // 2, cols // 2  # merged 2 x 2
        frame, cell, number, episode, subtask = button_tokens(args.root, rows, cols)
        press = torch.as_tensor(subtask == 2)
        y = torch.as_tensor(number)
        train = torch.as_tensor(episode < args.heldout_from)
        layers = {"merged": f.get_tensor("embeds")}
        for k, d in enumerate(f.get_tensor("deepstack")):
            layers[f"deepstack {k}"] = d
        for name, tokens in layers.items():
            if len(tokens) != int(frame.max()) + 1 and len(tokens) < int(frame.max()) + 1:
                raise SystemExit(f"{cache} holds {len(tokens)} frames: a cache of another build")
            x = tokens.float()[torch.as_tensor(frame), torch.as_tensor(cell)]
            pred = linear_probe(x, y, train)
            acc = [(pred[m] == y[m]).float().mean().item() for m in (train, ~train, ~train & press)]
            print(f"| {cache.name} | {name} | {acc[0]:.3f} | {acc[1]:.3f} | {acc[2]:.3f} | {len(y)} |")


if __name__ == "__main__":
    main()
