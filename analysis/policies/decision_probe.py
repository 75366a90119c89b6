"""Does a trained ActiveArena-VLA know the count when it must choose the button? A linear probe on the
count task's decision frames of a built dataset.

    python analysis/policies/decision_probe.py --root outputs/datasets/cpu_count_192 \\
        RUN_A/checkpoints/012000/pretrained_model RUN_B/checkpoints/003000/pretrained_model

For every episode it takes the frame ``--offset`` steps after the expert's press subtask begins (the
blocks are counted, the view is on the buttons, the arm has not moved yet: the decision), runs the
policy on it as in training (its memory frames from the dataset), and keeps the last-layer states at
the action queries (their mean). A logistic regression from those states to the number of target
blocks, cross-validated over episodes (at its best of a few L2 weights: an upper bound), says whether
the count is linearly readable where the policy decides; the majority class is the floor. The same
for the matching button's place among the three (by azimuth: the decision itself), from the states,
from the predicted chunk, and from the expert's recorded chunk at the same frames (the control:
what a policy that has decided shows).
"""

from __future__ import annotations

import argparse
from collections import Counter
from pathlib import Path

import numpy as np
import torch

TASK = "count_target_press_button"


def count_and_button(seed: int, split: str) -> tuple[int, int]:
    """The scene's number of target blocks, and where the matching button lies among the three
    (0, 1, 2 by azimuth): the decision the press makes."""
    from lerobot_activearena.tasks.registry import get_task
    from lerobot_activearena.tasks.sampling import sample_scene

    scene = sample_scene(get_task(TASK), seed, split)
    count = int(scene.params["count"])
    buttons = sorted((p["angle"], p["name"]) for p in scene.params["placements"] if p["category"] == "button")
    return count, [name for _, name in buttons].index(f"button_{count}")


def decision_frames(root: Path, offset: int) -> tuple[list[int], list[tuple[int, int]]]:
    """Dataset indices of each episode's decision frame, and the episode's count and button."""
    import json

    import pandas as pd

    frame = pd.concat(pd.read_parquet(f) for f in sorted(root.glob("data/*/*.parquet")))
    episodes = [json.loads(line) for line in (root / "meta/activearena/episodes.jsonl").open()]
    indices, counts = [], []
    for ep in episodes:
        g = frame[frame["episode_index"] == ep["episode_index"]].sort_values("frame_index")
        press = np.flatnonzero(g["subtask_index"].to_numpy() == 2)
        if len(press) == 0:
            continue
        indices.append(int(g["index"].to_numpy()[min(press[0] + offset, len(g) - 1)]))
        counts.append(count_and_button(ep["seed"], ep["split"]))
    return indices, counts


def features(policy_dir: Path, repo_id: str, root: Path, indices: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """(episodes, width) mean action-query states, (episodes, chunk * dims) predicted chunks and the
    recorded ones."""
    from lerobot.configs.policies import PreTrainedConfig
    from lerobot.datasets.factory import resolve_delta_timestamps
    from lerobot.datasets.lerobot_dataset import LeRobotDataset, LeRobotDatasetMetadata
    from lerobot.policies import make_policy, make_pre_post_processors

    from lerobot_activearena.eval.learning_curve import policy_inputs
    from lerobot_activearena.eval.protocol import register_policy_types

    register_policy_types()
    cfg = PreTrainedConfig.from_pretrained(policy_dir)
    cfg.pretrained_path, cfg.device = Path(policy_dir), "cpu"
    meta = LeRobotDatasetMetadata(repo_id, root=root)
    policy = make_policy(cfg, ds_meta=meta).eval()
    pre, _ = make_pre_post_processors(cfg, pretrained_path=cfg.pretrained_path)
    ds = LeRobotDataset(repo_id, root=root, delta_timestamps=resolve_delta_timestamps(cfg, meta))
    loader = torch.utils.data.DataLoader(torch.utils.data.Subset(ds, indices), batch_size=16)
    states, chunks, recorded = [], [], []
    decode = policy.decode_actions

    def keep(hidden, kind):
        from lerobot_activearena.policies.activearena_vla.modeling_activearena_vla import QUERY

        states.append(hidden[kind == QUERY].view(kind.shape[0], -1, hidden.shape[-1]).float().mean(1))
        return decode(hidden, kind)

    policy.decode_actions = keep
    with torch.no_grad():
        for batch in loader:
            chunks.append(policy.predict_action_chunk(pre(policy_inputs(batch, cfg))).flatten(1))
            recorded.append(batch["action"].flatten(1))
    return torch.cat(states).numpy(), torch.cat(chunks).numpy(), torch.cat(recorded).numpy()


def fit_probe(x: np.ndarray, y: np.ndarray, l2: float):
    """A multinomial logistic regression (standardised inputs, L2); returns its predict function."""
    classes = sorted(set(y.tolist()))
    target = torch.tensor([classes.index(v) for v in y])
    mu, sd = x.mean(0), x.std(0) + 1e-6
    xt = torch.tensor((x - mu) / sd, dtype=torch.float32)
    lin = torch.nn.Linear(x.shape[1], len(classes))
    opt = torch.optim.LBFGS(lin.parameters(), max_iter=200)

    def closure():
        opt.zero_grad()
        loss = torch.nn.functional.cross_entropy(lin(xt), target) + l2 * lin.weight.square().sum()
        loss.backward()
        return loss

    opt.step(closure)

    def predict(v: np.ndarray) -> np.ndarray:
        with torch.no_grad():
            out = lin(torch.tensor((v - mu) / sd, dtype=torch.float32)).argmax(1).numpy()
        return np.array(classes)[out]

    return predict


def cv_accuracy(x: np.ndarray, y: np.ndarray, l2: float, folds: int = 5, seed: int = 0) -> float:
    order = np.random.default_rng(seed).permutation(len(y))
    correct = 0
    for k in range(folds):
        test = order[k::folds]
        train = np.setdiff1d(order, test)
        correct += int((fit_probe(x[train], y[train], l2)(x[test]) == y[test]).sum())
    return correct / len(y)


def best_probe(x: np.ndarray, y: np.ndarray, x_out=None, y_out=None) -> str:
    """The probe's cross-validated accuracy at its best L2 weight (an upper bound: chosen on the same
    folds); with held-out episodes, the accuracy there of the probe fitted on all of ``x`` at that weight."""
    scores = {l2: cv_accuracy(x, y, l2) for l2 in L2_WEIGHTS}
    l2 = max(scores, key=scores.get)
    text = f"{scores[l2]:.0%}"
    if x_out is not None:
        text += f" / held-out {(fit_probe(x, y, l2)(x_out) == y_out).mean():.0%}"
    return text


L2_WEIGHTS = (1e-3, 1e-2, 1e-1, 1.0)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("checkpoints", nargs="+", type=Path, help="ActiveArena-VLA pretrained_model folders")
    p.add_argument("--root", type=Path, required=True, help="a count-task build (with meta/activearena)")
    p.add_argument("--repo-id", default=None, help="default: local/<root folder name>")
    p.add_argument("--offset", type=int, default=10, help="frames after the press subtask begins")
    p.add_argument(
        "--heldout-root", type=Path, help="a build of other seeds: the probes fitted above, tested there"
    )
    args = p.parse_args()
    repo_id = args.repo_id or f"local/{args.root.name}"
    indices, labels = decision_frames(args.root, args.offset)
    targets = {"count": np.array([c for c, _ in labels]), "button": np.array([b for _, b in labels])}
    held = {}
    if args.heldout_root is not None:
        h_indices, h_labels = decision_frames(args.heldout_root, args.offset)
        held = {"count": np.array([c for c, _ in h_labels]), "button": np.array([b for _, b in h_labels])}
    for name, y in targets.items():
        floor = Counter(y.tolist()).most_common(1)[0][1] / len(y)
        print(
            f"{len(y)} episodes, {name} {dict(sorted(Counter(y.tolist()).items()))}: majority class {floor:.0%}"
        )
    print(
        "probe accuracy, cross-validated over the build's episodes at the best L2 weight"
        + (f" / fitted there, tested on {len(held['count'])} held-out episodes:" if held else ":")
    )

    def probes(data, out=None) -> str:
        return ", ".join(
            f"{n} {best_probe(data, y, *((out, held[n]) if out is not None else ()))}"
            for n, y in targets.items()
        )

    for i, ckpt in enumerate(args.checkpoints):
        x, chunk, expert = features(ckpt, repo_id, args.root, indices)
        hx = hchunk = hexpert = None
        if held:
            hx, hchunk, hexpert = features(
                ckpt, f"local/{args.heldout_root.name}", args.heldout_root, h_indices
            )
        if i == 0:
            print(f"  the expert's recorded chunk: {probes(expert, hexpert)}")
        print(f"  {ckpt} action-query states: {probes(x, hx)}")
        print(f"  {ckpt} predicted chunk: {probes(chunk, hchunk)}")


if __name__ == "__main__":
    main()
