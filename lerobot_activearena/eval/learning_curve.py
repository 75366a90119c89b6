"""Learning curve of a lerobot-train run: its checkpoints, the open-loop action error of one on
held-out episodes (the chunk a policy predicts from a recorded frame against the chunk the expert
then executed, in joint units), and the plot of both against the closed-loop success that
``activearena-learning-curve`` measures with ``activearena-eval``."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np

from ..sim.action import ACTION_DIM, GRIPPER_INDICES, HEAD_PITCH, TORSO_YAW

# action groups the open-loop error is reported by
GROUPS = {
    "arms": [i for i in range(ACTION_DIM) if i not in (*GRIPPER_INDICES, TORSO_YAW, HEAD_PITCH)],
    "grippers": list(GRIPPER_INDICES),
    "view": [TORSO_YAW, HEAD_PITCH],
}


def checkpoints(train_dir: Path) -> list[tuple[int, Path]]:
    """``(step, pretrained_model folder)`` of every numbered checkpoint of a lerobot-train run."""
    out = []
    for d in sorted((Path(train_dir) / "checkpoints").iterdir()):
        model = d / "pretrained_model"
        if d.name.isdigit() and model.is_dir():
            out.append((int(d.name), model))
    if not out:
        raise FileNotFoundError(
            f"no checkpoints in {train_dir}/checkpoints (is it a lerobot-train output_dir?)"
        )
    return out


def image_size(policy_dir: Path) -> tuple[int, int]:
    """(height, width) of the head images a checkpoint was trained on."""
    from lerobot.configs.policies import PreTrainedConfig

    from .protocol import register_policy_types

    register_policy_types()  # a config names its type: LeRobot's and the plugins' must be known
    cfg = PreTrainedConfig.from_pretrained(policy_dir)
    _, h, w = cfg.input_features["observation.images.head"].shape
    return int(h), int(w)


def policy_inputs(batch: dict, cfg) -> dict:
    """A dataset batch's observations as a policy's preprocessor takes them at evaluation: its input
    features, the task text and the ``*_is_pad`` flags of the history frames."""
    obs = {k: v for k, v in batch.items() if k.startswith("observation.") and k in cfg.input_features}
    obs["task"] = batch["task"]
    obs.update({k: v for k, v in batch.items() if k.startswith("observation.") and k.endswith("_is_pad")})
    return obs


def read_annotations_from(pre, repo_id: str, root: Path) -> None:
    """Point an ActiveArena-VLA preprocessor's annotation step (subtask text, keyframe memories) at the
    dataset being scored: as saved, it reads the training build's, whose frames the indices of
    another build do not name. A vision cache's frame indices likewise: the history comes as images."""
    from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import (
        ActiveArenaAnnotationStep,
    )

    for step in pre.steps:
        if isinstance(step, ActiveArenaAnnotationStep):
            step.dataset_root, step.repo_id, step._ann = str(root), repo_id, None
            step.cached_memory = False


def scoring_policy(policy_dir: Path, repo_id: str, root: Path, memory_ablation: str = "none"):
    """A checkpoint loaded to score dataset frames as it acts in an env: ``(cfg, policy, pre, post, ds)``
    with ``ds`` the dataset at its own delta timestamps. A policy trained on a vision table loads its
    history as images (the table indexes the training build's frames; its memory tower reads them), and
    the annotation step reads ``root``'s. ``memory_ablation="blank"``: the memory frames come gray."""
    from lerobot.configs.policies import PreTrainedConfig
    from lerobot.datasets.factory import resolve_delta_timestamps
    from lerobot.datasets.lerobot_dataset import LeRobotDataset, LeRobotDatasetMetadata
    from lerobot.policies import make_policy, make_pre_post_processors

    from .protocol import register_policy_types

    register_policy_types()
    cfg = PreTrainedConfig.from_pretrained(policy_dir)
    if memory_ablation != "none":  # through the config's checks (a memory-free policy has none to blank)
        cfg = dataclasses.replace(cfg, memory_ablation=memory_ablation)
    cfg.pretrained_path, cfg.device = Path(policy_dir), "cpu"
    if getattr(cfg, "vision_cache", None):  # the delta timestamps then load the history as images
        cfg.vision_cache = None
    meta = LeRobotDatasetMetadata(repo_id, root=root)
    policy = make_policy(cfg, ds_meta=meta).eval()
    pre, post = make_pre_post_processors(cfg, pretrained_path=cfg.pretrained_path)
    read_annotations_from(pre, repo_id, root)
    ds = LeRobotDataset(repo_id, root=root, delta_timestamps=resolve_delta_timestamps(cfg, meta))
    return cfg, policy, pre, post, ds


def chunk_errors(
    policy_dir: Path, repo_id: str, root: Path, batch_size: int = 32, memory_ablation: str = "none"
):
    """Per dataset batch (in order): the batch and the absolute error between the predicted and the
    recorded action chunk, (B, steps, ACTION_DIM) in joint units, zero on padded steps past an
    episode's end, with the (B, steps, 1) mask of the real steps. History policies get the batch's
    ``*_is_pad`` flags, so frames before an episode's start are dropped as in training.
    ``memory_ablation="blank"``: the memory frames reach the policy as gray images."""
    import torch

    cfg, policy, pre, post, ds = scoring_policy(policy_dir, repo_id, root, memory_ablation)
    loader = torch.utils.data.DataLoader(ds, batch_size=batch_size, shuffle=False, num_workers=0)
    with torch.no_grad():
        for batch in loader:
            pred = post(policy.predict_action_chunk(pre(policy_inputs(batch, cfg)))).cpu().numpy()
            target, pad = batch["action"].numpy(), batch["action_is_pad"].numpy()
            steps = min(pred.shape[1], target.shape[1])
            valid = ~pad[:, :steps, None]
            yield batch, np.abs(pred[:, :steps] - target[:, :steps]) * valid, valid


def open_loop_error(policy_dir: Path, repo_id: str, root: Path, batch_size: int = 32) -> dict:
    """Mean absolute error between the predicted and the recorded action chunk over every frame of a
    dataset (padded steps past an episode's end excluded), overall and per action group."""
    total = np.zeros(ACTION_DIM)
    count = np.zeros(ACTION_DIM)
    frames = 0
    for _, err, valid in chunk_errors(policy_dir, repo_id, root, batch_size):
        total += err.sum(axis=(0, 1))
        count += np.broadcast_to(valid, err.shape).sum(axis=(0, 1))
        frames += len(err)
    per_dim = total / np.maximum(count, 1)
    return {
        "frames": frames,
        "l1": float(per_dim.mean()),
        **{f"l1_{name}": float(per_dim[idx].mean()) for name, idx in GROUPS.items()},
    }


def plot_curve(records: list[dict], path: Path, title: str) -> None:
    """Closed-loop ID success and held-out open-loop error against training steps."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    steps = [r["step"] for r in records]
    fig, ax = plt.subplots(figsize=(7, 4), dpi=120)
    success = [r["closed_loop"]["success"] for r in records]
    last = records[-1]["closed_loop"]
    indices = last.get("indices", f"0-{last['episodes'] - 1}")
    ax.plot(steps, success, "o-", color="tab:blue", label=f"ID success (manifest episodes {indices})")
    ax.set_xlabel("training step")
    ax.set_ylabel("success (%)", color="tab:blue")
    ax.set_ylim(-2, 102)
    ax.grid(alpha=0.3)
    if all("open_loop" in r for r in records):
        ax2 = ax.twinx()
        for name, style in (("l1", "k-"), ("l1_view", "--"), ("l1_arms", ":")):
            ax2.plot(steps, [r["open_loop"][name] for r in records], style, label=f"held-out {name}")
        ax2.set_ylabel("open-loop |error| (rad; grippers 0-1)")
        ax2.set_yscale("log")
        lines = ax.get_legend_handles_labels()
        lines2 = ax2.get_legend_handles_labels()
        ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], fontsize=8, loc="center right")
    else:
        ax.legend(fontsize=8)
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def read_curve(curve_dir: Path) -> list[dict]:
    """The records of a learning curve's ``curve.jsonl``, by step; a clear error if there are none."""
    path = Path(curve_dir) / "curve.jsonl"
    if not path.is_file():
        raise FileNotFoundError(f"{path} not found: give a folder activearena-learning-curve wrote")
    records = [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
    if not records:
        raise ValueError(f"{path} holds no checkpoint yet")
    return sorted(records, key=lambda r: r["step"])


def best_checkpoint(records: list[dict]) -> dict:
    """The record of the checkpoint to choose: the highest closed-loop success, the latest of a tie."""
    return max(records, key=lambda r: (r["closed_loop"]["success"], r["step"]))


def plot_overlay(curves: list[tuple[str, list[dict]]], path: Path, title: str) -> None:
    """Closed-loop success of several runs against training steps on one axis (a pair's curves side
    by side); each label names the episodes its points were scored on."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4), dpi=120)
    for label, records in curves:
        last = records[-1]["closed_loop"]
        indices = last.get("indices", f"0-{last['episodes'] - 1}")
        steps = [r["step"] for r in records]
        success = [r["closed_loop"]["success"] for r in records]
        ax.plot(steps, success, "o-", label=f"{label} (ID episodes {indices})")
    ax.set_xlabel("training step")
    ax.set_ylabel("success (%)")
    ax.set_ylim(-2, 102)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
