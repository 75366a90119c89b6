"""`activearena_fast` on the tiny random Qwen3-VL with a FAST tokenizer fitted on the builder dataset:
the extended vocabulary, the ``<think>..</think><action>..</action>`` target under one cross-entropy,
cached decoding equal to full re-encoding, a response that does not decode holding the last command
(counted), and the preset through lerobot-train, lerobot-eval and activearena-eval."""

import json
from pathlib import Path

import numpy as np
import pytest
import torch
from helpers.params import DATASET_REPO
from helpers.policy_runs import build_policy, collate, play_both, preset_config, train_preset
from lerobot.configs.types import NormalizationMode
from lerobot.datasets.dataset_metadata import LeRobotDatasetMetadata
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.policies.factory import make_policy, make_pre_post_processors
from lerobot.utils.constants import ACTION

from lerobot_activearena.cli.fit_fast_tokenizer import fit
from lerobot_activearena.policies.activearena_fast import ActiveArenaFASTConfig
from lerobot_activearena.policies.activearena_fast.processor_activearena_fast import HOLD_COMMAND
from lerobot_activearena.policies.activearena_vla.modeling_activearena_vla import QUERY, THINK
from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import RAW_STATE

PRESET = Path(__file__).parents[2] / "configs" / "policy" / "fast_subtask_action_12_ws.json"
SMALL = {"state_hidden": 32, "subtask_max_tokens": 6, "max_action_tokens": 12}


@pytest.fixture(scope="module")
def action_tokenizer(bell_count_dataset, tmp_path_factory):
    out = tmp_path_factory.mktemp("fast") / "tokenizer"
    fit(
        [
            "--repo-id",
            DATASET_REPO,
            "--root",
            str(bell_count_dataset),
            "--out",
            str(out),
            "--vocab-size",
            "400",
            "--holdout",
            "2",
        ]
    )
    return out


def test_the_preset_is_the_papers_run():
    cfg = preset_config(PRESET, ActiveArenaFASTConfig)
    assert cfg.type == "activearena_fast" and (cfg.think, cfg.memory, cfg.history, cfg.use_state) == (
        "subtask",
        "chunk",
        12,
        True,
    )
    assert cfg.action_vocab_size == 2048 and cfg.lm_loss_weight == 1.0
    with pytest.raises(ValueError, match="lm_loss_weight"):  # one cross-entropy: a weight would do nothing
        ActiveArenaFASTConfig(lm_loss_weight=0.1, device="cpu")
    with pytest.raises(ValueError, match="activearena_oft"):  # the subtask write policy is OFT's
        ActiveArenaFASTConfig(memory="subtask", device="cpu")
    assert cfg.normalization_mapping["ACTION"] == NormalizationMode.MIN_MAX  # as the tokenizer is fitted
    with pytest.raises(ValueError, match="think"):
        ActiveArenaFASTConfig(think="none")


def test_one_cross_entropy_over_think_and_action_tokens(tiny_vlm, bell_count_dataset, action_tokenizer):
    meta = LeRobotDatasetMetadata(DATASET_REPO, root=bell_count_dataset)
    cfg = ActiveArenaFASTConfig(
        vlm_path=str(tiny_vlm), action_tokenizer_path=str(action_tokenizer), device="cpu", history=2, **SMALL
    )
    with pytest.raises(ValueError, match="activearena-fit-fast-tokenizer"):
        make_policy(ActiveArenaFASTConfig(vlm_path=str(tiny_vlm), device="cpu"), ds_meta=meta)
    policy, pre, post, ds = build_policy(cfg, bell_count_dataset)
    text_rows = policy.action_token_base
    assert policy.vlm.get_input_embeddings().weight.shape[0] == text_rows + 2048
    assert policy.vlm.lm_head.weight.shape[0] == text_rows + 2048
    batch = collate(ds, pre, [70, len(ds) - 40])
    assert batch[ACTION].abs().max() <= 1 + 1e-5  # min-max normalised
    args = policy.training_args(batch)
    seq = policy.assemble(*args)
    assert not (seq["kind"] == QUERY).any()
    span = seq["input_ids"][0][seq["kind"][0] == THINK].tolist()
    codes = [t for t in span if t >= text_rows]
    assert codes == policy.action_token_ids(batch[ACTION][0].numpy())
    text = policy.text_tokenizer.decode([t for t in span if t < text_rows])
    assert text.startswith("<think>") and text.endswith("</think><action></action><|im_end|>"), text
    chunk = policy.decode_response(span)  # the target spells the batch's chunk
    np.testing.assert_allclose(chunk, batch[ACTION][0].numpy(), atol=0.06)
    cut = span[: span.index(codes[-1])]
    assert policy.decode_response(cut) is None
    assert policy.decode_response([*codes[:1], 5, *codes[1:]]) is None  # text inside the action span

    loss, info = policy.forward(batch)
    assert torch.isfinite(loss) and info["ce_loss"] > 0
    loss.backward()
    grad = policy.vlm.get_input_embeddings().weight.grad
    assert grad[codes].abs().sum() > 0  # the new action rows learn

    policy.eval()
    one = pre(torch.utils.data.default_collate([ds[70]]))
    enc = (
        one["observation.vlm.pixel_values"],
        one["observation.vlm.image_grid_thw"],
        one["observation.vlm.frame_valid"],
        one["observation.state"],
        one["observation.vlm.prefix_ids"],
        one["observation.vlm.prompt_ids"],
        one["observation.vlm.prompt_mask"],
    )
    assert policy.decode(enc, use_cache=True) == policy.decode(enc, use_cache=False)


def test_overfitting_one_sample_decodes_its_chunk(tiny_vlm, bell_count_dataset, action_tokenizer):
    """The whole path works: the cross-entropy falls, and greedy decoding then spells the sample's
    chunk (to the tokenizer's precision) with no failed decode."""
    cfg = ActiveArenaFASTConfig(
        vlm_path=str(tiny_vlm),
        action_tokenizer_path=str(action_tokenizer),
        device="cpu",
        memory="none",
        state_hidden=32,
        subtask_max_tokens=24,
        max_action_tokens=48,
    )
    policy, pre, _, ds = build_policy(cfg, bell_count_dataset)
    batch = collate(ds, pre, [70])
    opt = torch.optim.AdamW(policy.parameters(), lr=3e-3)
    policy.train()
    losses = []
    for _ in range(200):
        loss, _ = policy.forward(batch)
        opt.zero_grad()
        loss.backward()
        opt.step()
        losses.append(loss.item())
        if losses[-1] < 0.015:
            break
    assert losses[-1] < 0.05 < losses[0], losses[::20]
    policy.eval()
    policy.reset()
    chunk = policy.predict_action_chunk(batch)
    assert policy.rollout_stats() == [{"chunks": 1, "failed_decodes": 0}]
    assert (chunk - batch[ACTION]).abs().max() < 0.06


def test_a_response_that_does_not_decode_holds_the_last_command(
    tiny_vlm, bell_count_dataset, action_tokenizer
):
    meta = LeRobotDatasetMetadata(DATASET_REPO, root=bell_count_dataset)
    cfg = ActiveArenaFASTConfig(
        vlm_path=str(tiny_vlm), action_tokenizer_path=str(action_tokenizer), device="cpu", history=2, **SMALL
    )
    torch.manual_seed(0)
    policy = make_policy(cfg, ds_meta=meta)
    pre, post = make_pre_post_processors(cfg, dataset_stats=meta.stats)
    ds = LeRobotDataset(DATASET_REPO, root=bell_count_dataset, video_backend="pyav")
    frame = ds[30]
    obs = {k: frame[k][None] for k in ("observation.images.head", "observation.state")}
    obs["task"] = [frame["task"]]
    policy.eval()
    policy.reset()
    batch = pre(obs)
    first = post(policy.select_action(batch))  # the random backbone spells no chunk: hold the state
    torch.testing.assert_close(first[0], batch[RAW_STATE][0].float(), atol=1e-4, rtol=0)
    torch.testing.assert_close(batch[HOLD_COMMAND], pre(obs)[HOLD_COMMAND])
    for _ in range(16):
        last = post(policy.select_action(pre(obs)))
    torch.testing.assert_close(last, first)  # the next failed chunk holds the last command
    assert policy.rollout_stats() == [{"chunks": 2, "failed_decodes": 2}]
    policy.reset()
    assert policy.rollout_stats() == []


def test_the_preset_trains_saves_and_plays_through_both_evaluators(
    tiny_vlm, bell_count_dataset, action_tokenizer, tmp_path
):
    ckpt = train_preset(
        PRESET,
        bell_count_dataset,
        tiny_vlm,
        tmp_path / "train",
        f"--policy.action_tokenizer_path={action_tokenizer}",
        "--policy.history=2",
        *[f"--policy.{k}={v}" for k, v in SMALL.items()],
    )
    assert json.loads((ckpt / "config.json").read_text())["type"] == "activearena_fast"
    saved = ckpt / "action_tokenizer"
    assert (saved / "fast_tokenizer.json").read_text() == (
        action_tokenizer / "fast_tokenizer.json"
    ).read_text()
    config = json.loads((ckpt / "config.json").read_text())
    config["action_tokenizer_path"] = str(tmp_path / "gone")  # the checkpoint's own copy is used
    (ckpt / "config.json").write_text(json.dumps(config))
    _, mine = play_both(ckpt, tmp_path)
    assert mine["policy_stats"] == {"chunks": 1, "failed_decodes": 1}  # 16 steps: one chunk, random backbone
