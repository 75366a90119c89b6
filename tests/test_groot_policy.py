"""`activearena_groot` on the tiny random Qwen3-VL and a tiny DiT: the OFT run's inputs and memory
with the DiT head (no action queries in the sequence), flow-matching and think losses reaching the
head and the backbone, seeded sampling, and the preset through lerobot-train, lerobot-eval and
activearena-eval."""

import json
from pathlib import Path

import torch
from conftest import DATASET_REPO
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

from lerobot_activearena.cli.eval import main as activearena_eval
from lerobot_activearena.envs.configs import ActiveArenaEnvConfig
from lerobot_activearena.policies.activearena_groot import ActiveArenaGR00TConfig
from lerobot_activearena.policies.activearena_oft.modeling_activearena_oft import QUERY

PRESET = Path(__file__).parents[1] / "configs" / "policy" / "gr00t_subtask_action_12_ws.json"
TINY_DIT = {
    "dit_width": 32,
    "dit_depth": 2,
    "dit_heads": 2,
    "dit_queries": 4,
    "dit_out_dim": 32,
    "decoder_width": 32,
    "noise_repeats": 2,
}


def test_the_preset_is_the_papers_head():
    policy = json.loads(PRESET.read_text())["policy"]
    cfg = ActiveArenaGR00TConfig(**{k: v for k, v in policy.items() if k != "type"}, device="cpu")
    assert cfg.type == "activearena_groot" and (cfg.think, cfg.memory, cfg.history, cfg.use_state) == (
        "subtask",
        "chunk",
        12,
        True,
    )
    head = cfg.dit_config(context_dim=2048)
    assert (head.depth, head.width, head.heads, head.queries, head.out_dim) == (16, 768, 12, 32, 1024)
    assert (head.noise_repeats, head.inference_steps, head.dropout) == (8, 4, 0.2)


def test_losses_reach_the_head_and_backbone_and_a_seed_fixes_the_chunk(tiny_vlm, bell_count_dataset):
    meta = LeRobotDatasetMetadata(DATASET_REPO, root=bell_count_dataset)
    cfg = ActiveArenaGR00TConfig(
        vlm_path=str(tiny_vlm), device="cpu", state_hidden=32, history=4, think="subtask", **TINY_DIT
    )
    torch.manual_seed(0)
    policy = make_policy(cfg, ds_meta=meta)
    pre, _ = make_pre_post_processors(cfg, dataset_stats=meta.stats)
    ds = LeRobotDataset(
        DATASET_REPO,
        root=bell_count_dataset,
        video_backend="pyav",
        delta_timestamps=resolve_delta_timestamps(cfg, meta),
    )
    batch = pre(torch.utils.data.default_collate([ds[70], ds[len(ds) - 40]]))
    assert not hasattr(policy, "action_queries") and not hasattr(policy, "head")
    loss, info = policy.forward(batch)
    assert torch.isfinite(loss) and info["flow_loss"] > 0 and info["lm_loss"] > 0
    loss.backward()
    params = dict(policy.named_parameters())
    for name in ("dit.blocks.0.k.weight", "dit.decoder.2.weight", "state_encoder.mlp.0.weight"):
        assert params[name].grad is not None and params[name].grad.abs().sum() > 0, name
    assert policy.vlm.get_input_embeddings().weight.grad.abs().sum() > 0
    seq = policy._assemble(*policy.training_args(batch))
    assert not (seq["kind"] == QUERY).any()  # the DiT keeps its own queries
    policy.eval()
    one = pre(torch.utils.data.default_collate([ds[70]]))
    chunks = []
    for seed in (3, 3, 4):
        policy.reset()
        torch.manual_seed(seed)
        with torch.no_grad():
            chunks.append(policy.predict_action_chunk(one))
    assert chunks[0].shape == (1, 16, 18)
    torch.testing.assert_close(chunks[0], chunks[1])
    assert not torch.allclose(chunks[0], chunks[2])


def test_the_preset_trains_saves_and_plays_through_both_evaluators(tiny_vlm, bell_count_dataset, tmp_path):
    train_dir = tmp_path / "train"
    cfg = TrainPipelineConfig.from_pretrained(
        PRESET,
        cli_args=[
            f"--dataset.repo_id={DATASET_REPO}",
            f"--dataset.root={bell_count_dataset}",
            f"--policy.vlm_path={tiny_vlm}",
            "--policy.device=cpu",
            "--policy.state_hidden=32",
            "--policy.history=2",
            *[f"--policy.{k}={v}" for k, v in TINY_DIT.items()],
            "--steps=2",
            "--batch_size=2",
            "--num_workers=0",
            "--save_freq=2",
            "--log_freq=1",
            f"--output_dir={train_dir}",
        ],
    )
    lerobot_train(cfg)
    ckpt = train_dir / "checkpoints" / "last" / "pretrained_model"
    saved = json.loads((ckpt / "config.json").read_text())
    assert saved["type"] == "activearena_groot" and saved["dit_width"] == 32

    policy = PreTrainedConfig.from_pretrained(ckpt)
    policy.pretrained_path, policy.device = ckpt, "cpu"
    out = tmp_path / "eval"
    env = ActiveArenaEnvConfig(
        task="click_bell_rotate_view", episode_length=16, episode_log_dir=str(out / "episodes")
    )
    lerobot_eval_main(
        EvalPipelineConfig(
            env=env, policy=policy, eval=EvalConfig(n_episodes=1, batch_size=1), output_dir=out, seed=1000
        )
    )
    assert json.loads((out / "eval_info.json").read_text())["overall"]["n_episodes"] == 1
    run = tmp_path / "protocol"
    activearena_eval(
        [
            f"--policy.path={ckpt}",
            "--policy.device=cpu",
            "--tasks=click_bell_rotate_view",
            "--env.episode_length=16",
            "--splits=id",
            "--episodes=1",
            "--videos=0",
            f"--out={run}",
        ]
    )
    theirs = json.loads(next((out / "episodes").glob("*.jsonl")).read_text().splitlines()[0])
    mine = json.loads((run / "id" / "episodes" / "records.jsonl").read_text().splitlines()[0])
    for key in ("scene_seed", "steps", "success"):
        assert mine[key] == theirs[key], key
