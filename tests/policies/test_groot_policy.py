"""`activearena_groot` on the tiny random Qwen3-VL and a tiny DiT: the OFT run's inputs and memory
with the DiT head (no action queries in the sequence), flow-matching and think losses reaching the
head and the backbone, seeded sampling, and the preset through lerobot-train, lerobot-eval and
activearena-eval."""

import json
from pathlib import Path

import torch
from helpers.policy_runs import build_policy, collate, play_both, preset_config, train_preset

from lerobot_activearena.policies.activearena_groot import ActiveArenaGR00TConfig
from lerobot_activearena.policies.activearena_vla.modeling_activearena_vla import QUERY

PRESET = Path(__file__).parents[2] / "configs" / "policy" / "gr00t_subtask_action_12_ws.json"
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
    cfg = preset_config(PRESET, ActiveArenaGR00TConfig)
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
    cfg = ActiveArenaGR00TConfig(
        vlm_path=str(tiny_vlm), device="cpu", state_hidden=32, history=4, think="subtask", **TINY_DIT
    )
    policy, pre, _, ds = build_policy(cfg, bell_count_dataset)
    batch = collate(ds, pre, [70, len(ds) - 40])
    assert not hasattr(policy, "action_queries") and not hasattr(policy, "head")
    loss, info = policy.forward(batch)
    assert torch.isfinite(loss) and info["flow_loss"] > 0 and info["lm_loss"] > 0
    loss.backward()
    params = dict(policy.named_parameters())
    for name in ("dit.blocks.0.k.weight", "dit.decoder.2.weight", "state_encoder.mlp.0.weight"):
        assert params[name].grad is not None and params[name].grad.abs().sum() > 0, name
    assert policy.vlm.get_input_embeddings().weight.grad.abs().sum() > 0
    seq = policy.assemble(*policy.training_args(batch))
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
    tiny = [f"--policy.{k}={v}" for k, v in TINY_DIT.items()]
    ckpt = train_preset(
        PRESET,
        bell_count_dataset,
        tiny_vlm,
        tmp_path / "train",
        "--policy.state_hidden=32",
        "--policy.history=2",
        *tiny,
    )
    saved = json.loads((ckpt / "config.json").read_text())
    assert saved["type"] == "activearena_groot" and saved["dit_width"] == 32
    play_both(ckpt, tmp_path)
