"""Shared steps of the policy-preset tests: a preset through ``lerobot-train`` for 2 steps on the tiny
backbone, then its checkpoint through LeRobot's eval loop and through activearena-eval on the same
seed (one short episode each)."""

import json
from pathlib import Path

import torch
from lerobot.configs.default import EvalConfig
from lerobot.configs.eval import EvalPipelineConfig
from lerobot.configs.policies import PreTrainedConfig
from lerobot.configs.train import TrainPipelineConfig
from lerobot.datasets.dataset_metadata import LeRobotDatasetMetadata
from lerobot.datasets.factory import resolve_delta_timestamps
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.policies.factory import make_policy, make_pre_post_processors
from lerobot.scripts.lerobot_eval import eval_main as lerobot_eval_main
from lerobot.scripts.lerobot_train import train as lerobot_train

from helpers.params import DATASET_REPO
from lerobot_activearena.cli.eval import main as activearena_eval
from lerobot_activearena.envs.configs import ActiveArenaEnvConfig

PRESETS = Path(__file__).parents[2] / "configs" / "policy"
TASK = "click_bell_rotate_view"
RUNS = [  # the paper's table "Complete internal-baseline manifest"
    "oft_instruction_action_12_ws",
    "oft_no_action_12_ws",
    "oft_subtask_no_0_ws",
    "oft_subtask_action_12_wos",
    "oft_subtask_action_12_ws",
    "oft_subtask_action_6_ws",
    "oft_subtask_motion_12_ws",
    "oft_subtask_motion_6_ws",
    "oft_subtask_subtask_12_ws",
    "oft_subtask_subtask_6_ws",
    "gr00t_subtask_action_12_ws",
    "fast_subtask_action_12_ws",
    "oft_subtask_planned_12_ws",
]
FIXED = "oft_subtask_action_12_ws_fixed"  # ActiveArena-Fixed


def preset_config(path: Path, config_cls):
    """A preset file's policy section as ``config_cls`` on the CPU."""
    policy = json.loads(Path(path).read_text())["policy"]
    return config_cls(**{k: v for k, v in policy.items() if k != "type"}, device="cpu")


def policy_dataset(cfg, root: Path, meta: LeRobotDatasetMetadata) -> LeRobotDataset:
    """The builder dataset at ``root`` with ``cfg``'s history frames (``delta_timestamps``)."""
    return LeRobotDataset(
        DATASET_REPO, root=root, video_backend="pyav", delta_timestamps=resolve_delta_timestamps(cfg, meta)
    )


def build_policy(cfg, root: Path):
    """``cfg``'s policy (torch seed 0) for the builder dataset at ``root``, its pre- and
    postprocessor, and that dataset with the policy's history."""
    meta = LeRobotDatasetMetadata(DATASET_REPO, root=root)
    torch.manual_seed(0)
    policy = make_policy(cfg, ds_meta=meta)
    pre, post = make_pre_post_processors(cfg, dataset_stats=meta.stats)
    return policy, pre, post, policy_dataset(cfg, root, meta)


def collate(ds, pre, indices) -> dict:
    """Samples ``indices`` of ``ds`` as one preprocessed batch."""
    return pre(torch.utils.data.default_collate([ds[i] for i in indices]))


def train_preset(preset: Path, dataset: Path, vlm: Path, out: Path, *extra: str) -> Path:
    """2 training steps at batch 2; returns the saved checkpoint folder."""
    cfg = TrainPipelineConfig.from_pretrained(
        preset,
        cli_args=[
            f"--dataset.repo_id={DATASET_REPO}",
            f"--dataset.root={dataset}",
            f"--policy.vlm_path={vlm}",
            "--policy.device=cpu",
            *extra,
            "--steps=2",
            "--batch_size=2",
            "--num_workers=0",
            "--save_freq=2",
            "--log_freq=1",
            f"--output_dir={out}",
        ],
    )
    lerobot_train(cfg)
    return out / "checkpoints" / "last" / "pretrained_model"


def play_both(ckpt: Path, out: Path, steps: int = 16) -> tuple[dict, dict]:
    """One episode of ``steps`` through lerobot-eval and one through activearena-eval; returns their
    episode records (lerobot-eval's env log, activearena-eval's merged record) after checking that
    they played the same scene for the same number of steps."""
    policy = PreTrainedConfig.from_pretrained(ckpt)
    policy.pretrained_path, policy.device = ckpt, "cpu"
    theirs_dir = out / "lerobot_eval"
    env = ActiveArenaEnvConfig(task=TASK, episode_length=steps, episode_log_dir=str(theirs_dir / "episodes"))
    lerobot_eval_main(
        EvalPipelineConfig(
            env=env,
            policy=policy,
            eval=EvalConfig(n_episodes=1, batch_size=1),
            output_dir=theirs_dir,
            seed=1000,
        )
    )
    assert json.loads((theirs_dir / "eval_info.json").read_text())["overall"]["n_episodes"] == 1
    run = out / "activearena_eval"
    activearena_eval(
        [
            f"--policy.path={ckpt}",
            "--policy.device=cpu",
            f"--tasks={TASK}",
            f"--env.episode_length={steps}",
            "--splits=id",
            "--episodes=1",
            "--videos=0",
            f"--out={run}",
        ]
    )
    theirs = json.loads(next((theirs_dir / "episodes").glob("*.jsonl")).read_text().splitlines()[0])
    mine = json.loads((run / "id" / "episodes" / "records.jsonl").read_text().splitlines()[0])
    for key in ("scene_seed", "steps", "success"):
        assert mine[key] == theirs[key], key
    return theirs, mine
