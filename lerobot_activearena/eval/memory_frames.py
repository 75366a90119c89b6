"""What a memory-aware policy had in memory when it decided: play one protocol episode with an
ActiveArena-VLA checkpoint through LeRobot's own rollout loop, then draw the frames of its memory bank
at the episode's last chunk decision, next to the frame it decided on and the final one."""

from __future__ import annotations

import json
import tempfile
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from ..annotations.keyframes import STRIDE, stride_sequence


@contextmanager
def policy_in_env(policy_path: Path, task: str, split: str, vlm_path: str | None = None, **env_options):
    """An ActiveArena-VLA checkpoint, its processors and one env of ``task`` at the checkpoint's image
    size, as ``lerobot-eval`` builds them; yields ``(policy, processors, vec_env, env_cfg, log_dir)``,
    ``processors`` in ``lerobot_eval.rollout``'s order. ``env_options``: more ``ActiveArenaEnvConfig``
    fields (e.g. ``expert_channel``)."""
    from lerobot.configs.policies import PreTrainedConfig
    from lerobot.envs.factory import make_env_pre_post_processors
    from lerobot.envs.utils import close_envs
    from lerobot.policies import make_policy, make_pre_post_processors

    from ..envs.configs import ActiveArenaEnvConfig
    from .learning_curve import image_size
    from .protocol import register_policy_types

    register_policy_types()
    cfg = PreTrainedConfig.from_pretrained(policy_path)
    if not hasattr(cfg, "memory"):
        raise ValueError(f"{policy_path} is a {cfg.type} checkpoint; the memory bank is ActiveArena-VLA's")
    cfg.pretrained_path, cfg.device = Path(policy_path), "cpu"
    overrides = {"device_processor": {"device": "cpu"}}
    if vlm_path is not None:
        cfg.vlm_path = vlm_path
        overrides["activearena_oft_vlm_inputs"] = {"vlm_path": vlm_path}  # every head registers it so
    height, width = image_size(Path(policy_path))
    with tempfile.TemporaryDirectory() as logs:
        env_cfg = ActiveArenaEnvConfig(
            task=task,
            split=split,
            observation_height=height,
            observation_width=width,
            episode_log_dir=logs,
            **env_options,
        )
        policy = make_policy(cfg=cfg, env_cfg=env_cfg).eval()
        pre, post = make_pre_post_processors(
            cfg, pretrained_path=str(policy_path), preprocessor_overrides=overrides
        )
        env_pre, env_post = make_env_pre_post_processors(env_cfg=env_cfg, policy_cfg=cfg)
        envs = env_cfg.create_envs(n_envs=1, use_async_envs=False)
        vec = next(iter(next(iter(envs.values())).values()))
        try:
            yield policy, (env_pre, env_post, pre, post), vec, env_cfg, Path(logs)
        finally:
            close_envs(envs)


def play_and_record(
    policy_path: Path,
    task: str,
    split: str,
    episode: int,
    vlm_path: str | None = None,
    episode_length: int | None = None,
) -> dict:
    """One manifest episode (``episode`` = its manifest index) at the checkpoint's image size. Returns
    the head frames per step, the memory bank's env steps after every step, the chunk size executed,
    and the episode's record (success, failure state and reason)."""
    import torch
    from lerobot.scripts import lerobot_eval
    from tqdm import trange

    lerobot_eval.trange = lambda *a, **k: trange(*a, **{**k, "disable": True})  # one episode: no bar
    frames: list[np.ndarray] = []
    banks: list[list[int]] = []
    with policy_in_env(policy_path, task, split, vlm_path, episode_length=episode_length) as (
        policy,
        processors,
        vec,
        env_cfg,
        logs,
    ):
        with torch.no_grad():
            lerobot_eval.rollout(
                vec,
                policy,
                *processors,
                seeds=[env_cfg.seed_base + episode],
                render_callback=lambda env: frames.append(env.envs[0].render()),
                predicted_latents_callback=lambda p: banks.append([e["t"] for e in p.memory(0)]),
            )
        record = json.loads(next(logs.rglob("*.jsonl")).read_text().splitlines()[0])
        chunk = policy.config.n_action_steps
        # chunk memory re-planning every n < 16 steps holds more frames than a decision reads
        read_stride = STRIDE if policy.config.memory == "chunk" else None
        history = policy.config.history
    return {
        "frames": frames,
        "banks": banks,
        "chunk": chunk,
        "record": record,
        "read_stride": read_stride,
        "history": history,
    }


def decision_step(n_steps: int, chunk: int) -> int:
    """The env step of the episode's last chunk prediction (chunks start at 0, chunk, 2 chunk, ...)."""
    return ((n_steps - 1) // chunk) * chunk


def decision_memory(played: dict) -> tuple[int, list[int]]:
    """The last decision's env step and the memory frames it read (env steps, oldest first)."""
    banks = played["banks"]
    t = decision_step(len(banks), played["chunk"])
    memory = [s for s in (banks[t - 1] if t > 0 else []) if s < t]
    if played.get("read_stride"):  # chunk memory: the frames 16, 32, ... steps back
        read = stride_sequence(t, played["read_stride"], played["history"])[:-1]
        memory = [s for s in memory if s in read]
    return t, memory


def draw_memory(played: dict, title: str, out: Path) -> Path:
    """The memory bank's frames used at the last decision (oldest first), the frame decided on and the
    final frame, in one labelled row."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    frames, rec = played["frames"], played["record"]
    n_steps = len(played["banks"])
    t, memory = decision_memory(played)
    panels = [(s, f"memory t={s}") for s in memory] + [
        (t, f"decides at t={t}"),
        (n_steps, f"end t={n_steps}"),
    ]
    fig, axes = plt.subplots(1, len(panels), figsize=(1.6 * len(panels), 1.6), squeeze=False)
    for ax, (step, label) in zip(axes[0], panels, strict=True):
        ax.imshow(frames[min(step, len(frames) - 1)])
        ax.set_title(label, fontsize=7)
        ax.axis("off")
    outcome = "success" if rec["success"] else f"{rec['failure_state']}: {rec['failure_reason']}"
    fig.suptitle(f"{title} ({outcome})", fontsize=8)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=150)
    plt.close(fig)
    return out
