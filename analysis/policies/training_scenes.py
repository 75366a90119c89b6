"""A checkpoint on the scenes of its own training episodes: does evaluation feed it what training did,
and where does its closed loop leave the demonstration?

    python analysis/policies/training_scenes.py --repo-id local/cpu_click_bell_200 \\
        --root outputs/datasets/cpu_click_bell_200_vla --episodes 0-9 CHECKPOINT

Per training episode (its scene seed re-played in the env):
- **parity**: the env replays the demonstration's actions while the policy observes every step as in
  ``lerobot-eval`` (its memory bank filled by ``select_action``); at each chunk boundary the chunk it
  predicts is compared with the chunk it predicts from the dataset sample of the same frame (history
  from the dataset's delta timestamps, as in training). Near zero means evaluation and training agree.
- **closed loop**: the policy drives the env itself; success, and how far its torso yaw and left arm
  (the bell's pressing arm) end from the demonstration's last frame (radians). With
  ``--show-demonstration image|state --at T`` the policy sees, at step T only, the demonstration's
  head image or state instead of its own: which of the two its decision there follows.
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

import numpy as np
import torch

from lerobot_activearena.cli.args import int_ranges
from lerobot_activearena.sim.action import HEAD_PITCH, TORSO_YAW

LEFT_ARM = slice(0, 7)


def env_batch(obs: dict, task_text: str, env_pre, pre) -> dict:
    """One env observation as ``lerobot-eval``'s rollout hands it to a policy."""
    from lerobot.envs.utils import preprocess_observation

    batched = {
        k: {kk: vv[None] for kk, vv in v.items()} if isinstance(v, dict) else v[None] for k, v in obs.items()
    }
    out = preprocess_observation(batched)
    out["task"] = [task_text]
    return pre(env_pre(out))


class TrainingScenes:
    """A checkpoint, the dataset it was trained on, and envs that re-play that dataset's scenes."""

    def __init__(self, checkpoint: Path, repo_id: str, root: Path):
        from lerobot.configs.policies import PreTrainedConfig
        from lerobot.datasets.factory import resolve_delta_timestamps
        from lerobot.datasets.lerobot_dataset import LeRobotDataset, LeRobotDatasetMetadata
        from lerobot.policies import make_policy, make_pre_post_processors

        from lerobot_activearena.eval.learning_curve import image_size
        from lerobot_activearena.eval.protocol import register_policy_types

        register_policy_types()
        self.cfg = PreTrainedConfig.from_pretrained(checkpoint)
        self.cfg.pretrained_path, self.cfg.device = Path(checkpoint), "cpu"
        meta = LeRobotDatasetMetadata(repo_id, root=root)
        self.policy = make_policy(self.cfg, ds_meta=meta).eval()
        self.pre, self.post = make_pre_post_processors(self.cfg, pretrained_path=checkpoint)
        self.ds = LeRobotDataset(
            repo_id, root=root, delta_timestamps=resolve_delta_timestamps(self.cfg, meta)
        )
        build = json.loads((Path(root) / "meta/activearena/build.json").read_text())
        if build["plan"].get("reading_variants", 1) > 1:
            raise SystemExit(
                f"{root} is a counterfactual build (--reading-variants): its episodes' scenes are not the env's "
                "scene seeds, so they cannot be replayed here"
            )
        lines = (Path(root) / "meta/activearena/episodes.jsonl").open()
        self.recorded = {e["episode_index"]: e for e in map(json.loads, lines)}
        self.size = image_size(checkpoint)

    def env(self, episode: int):
        """The env of the episode's task and split that plays scene seeds as given, and its processors."""
        from lerobot.envs.factory import make_env_pre_post_processors

        from lerobot_activearena.envs.configs import ActiveArenaEnvConfig
        from lerobot_activearena.envs.gym_env import ActiveArenaEnv

        info = self.recorded[episode]
        kwargs = {"task": info["task"], "split": info["split"], "use_manifest": False}
        kwargs |= {"observation_height": self.size[0], "observation_width": self.size[1]}
        return ActiveArenaEnv(**kwargs), *make_env_pre_post_processors(
            ActiveArenaEnvConfig(**kwargs), self.cfg
        )

    def frames(self, episode: int) -> range:
        """The episode's dataset indices."""
        eps = self.ds.meta.episodes
        return range(int(eps["dataset_from_index"][episode]), int(eps["dataset_to_index"][episode]))

    @torch.no_grad()
    def dataset_chunk(self, index: int) -> np.ndarray:
        """The chunk predicted from dataset sample ``index`` (its history from the delta timestamps)."""
        from lerobot_activearena.eval.learning_curve import policy_inputs

        sample = {k: v[None] if isinstance(v, torch.Tensor) else [v] for k, v in self.ds[index].items()}
        chunk = self.policy.predict_action_chunk(self.pre(policy_inputs(sample, self.cfg)))
        return self.post(chunk).numpy()[0]

    @torch.no_grad()
    def replay(self, episode: int, offset: int = 0) -> list[tuple[int, np.ndarray, np.ndarray]]:
        """The env replays the episode's recorded actions while the policy observes every step as in
        ``lerobot-eval``; at each chunk boundary t: (t, the chunk from the env's observation and the
        policy's memory bank, the chunk from dataset sample t + ``offset``)."""
        env, env_pre, _ = self.env(episode)
        obs, _ = env.reset(seed=self.recorded[episode]["seed"])
        self.policy.reset()
        frames, out = self.frames(episode), []
        for t, index in enumerate(frames):
            batch = env_batch(obs, env.task_description, env_pre, self.pre)
            if self.policy.queued_actions == 0:
                from_env = self.post(self.policy.predict_action_chunk(batch)).numpy()[0]
                out.append((t, from_env, self.dataset_chunk(frames[min(t + offset, len(frames) - 1)])))
            self.policy.select_action(batch)
            obs, *_ = env.step(self.ds.hf_dataset[index]["action"].numpy())
        env.close()
        return out

    def demonstration_observation(self, episode: int, t: int, obs: dict, show: str) -> dict:
        """``obs`` with the demonstration's step-t head image (``show="image"``: the dataset's decoded
        frame) or state (``show="state"``) in place of the env's own."""
        index = self.frames(episode)[t]
        out = dict(obs)
        if show == "state":
            out["agent_pos"] = (
                self.ds.hf_dataset[index]["observation.state"].numpy().astype(obs["agent_pos"].dtype)
            )
        elif show == "image":
            frame = self.ds[index]["observation.images.head"][-1].permute(1, 2, 0).numpy()
            out["pixels"] = dict(obs["pixels"], head=(frame * 255).round().astype(np.uint8))
        else:
            raise ValueError(f"show must be 'image' or 'state', got {show!r}")
        return out

    @torch.no_grad()
    def closed_loop(self, episode: int, show: str | None = None, at: int = 16) -> tuple[dict, np.ndarray]:
        """The policy drives the episode's scene to the end; the last step's info and state. With
        ``show``, at step ``at`` the policy sees the demonstration's image or state instead of its own
        (the env is not touched): which of the two its decision there follows."""
        env, env_pre, env_post = self.env(episode)
        obs, _ = env.reset(seed=self.recorded[episode]["seed"])
        self.policy.reset()
        done, info, t = False, {}, 0
        while not done:
            seen = self.demonstration_observation(episode, t, obs, show) if show and t == at else obs
            action = self.post(
                self.policy.select_action(env_batch(seen, env.task_description, env_pre, self.pre))
            )
            action = env_post({"action": action})["action"].numpy()[0]
            obs, _, terminated, truncated, info = env.step(action)
            done, t = terminated or truncated, t + 1
        env.close()
        return info, np.asarray(obs["agent_pos"])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("checkpoint", type=Path, help="a pretrained_model folder")
    p.add_argument("--repo-id", required=True)
    p.add_argument("--root", type=Path, required=True, help="the dataset the checkpoint was trained on")
    p.add_argument("--episodes", default="0-9", help="dataset episode indices, e.g. 0-9,20")
    p.add_argument(
        "--show-demonstration",
        choices=["image", "state"],
        help="in closed loop, at step --at the policy sees the demonstration's image or state",
    )
    p.add_argument("--at", type=int, default=16, help="the step of --show-demonstration (default 16)")
    args = p.parse_args()
    scenes = TrainingScenes(args.checkpoint, args.repo_id, args.root)
    episodes, wins = int_ranges(args.episodes), 0
    missing = sorted(set(episodes) - set(scenes.recorded))
    if missing:
        p.error(f"--episodes {missing} are not in {args.root} (it has {len(scenes.recorded)} episodes)")
    view = [TORSO_YAW, HEAD_PITCH]
    for ep in episodes:
        gaps = np.concatenate([np.abs(a - b) for _, a, b in scenes.replay(ep)])
        info, final = scenes.closed_loop(ep, args.show_demonstration, args.at)
        demo_final = scenes.ds.hf_dataset[scenes.frames(ep)[-1]]["observation.state"].numpy()
        success = bool(info.get("is_success"))
        wins += success
        outcome = "success" if success else f"failure {info.get('failure_state', '')}"
        print(
            f"episode {ep:3d} (seed {scenes.recorded[ep]['seed']}): |env - dataset chunk| left arm "
            f"{gaps[:, LEFT_ARM].max():.4f}, view {gaps[:, view].max():.4f}; closed loop {outcome}, torso ends "
            f"{final[TORSO_YAW] - demo_final[TORSO_YAW]:+.3f} rad from the demonstration's, left arm up to "
            f"{np.abs(final[LEFT_ARM] - demo_final[LEFT_ARM]).max():.3f} rad"
        )
    print(f"closed loop on training scenes: {wins} of {len(episodes)}")


if __name__ == "__main__":
    os.environ.setdefault("MUJOCO_GL", "egl")
    main()
