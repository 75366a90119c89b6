"""ActiveArena-Plan on the tiny random Qwen3-VL: the planner's training target (the paper's prompt,
subtask and retrieval positions from the dataset's keyframes), the executor's subtask prompt and
planned memory, the run-time loop (planner -> bank -> executor; malformed answers counted and
ignored), and both presets through lerobot-train, then lerobot-eval and activearena-eval running
planner and executor together."""

import json
from pathlib import Path

import pytest
import torch
from helpers.params import DATASET_REPO
from helpers.policy_runs import collate, play_both, policy_dataset, preset_config, train_preset
from lerobot.datasets.dataset_metadata import LeRobotDatasetMetadata
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.policies.factory import make_policy, make_pre_post_processors

from lerobot_activearena.annotations.keyframes import planned_memory, retrieval_positions
from lerobot_activearena.policies.activearena_oft import ActiveArenaOFTConfig
from lerobot_activearena.policies.activearena_plan import ActiveArenaPlanConfig
from lerobot_activearena.policies.activearena_planner import ActiveArenaPlannerConfig
from lerobot_activearena.policies.activearena_planner.answers import (
    PlannerAnswer,
    parse_planner_answer,
    planner_prompt,
    planner_target,
    stride_frames,
)
from lerobot_activearena.policies.activearena_vla.dataset_annotations import DatasetAnnotations
from lerobot_activearena.policies.activearena_vla.modeling_activearena_vla import THINK
from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import (
    FRAME_VALID,
    PROMPT_IDS,
    PROMPT_MASK,
)

PRESETS = Path(__file__).parents[2] / "configs" / "policy"
EXECUTOR, PLANNER = (
    PRESETS / "oft_subtask_planned_12_ws.json",
    PRESETS / "oft_subtask_planned_12_ws_planner.json",
)
FRAME = 70  # a frame of the first episode with history


def test_the_presets_are_the_papers_planner_and_executor():
    planner, executor = (
        preset_config(PLANNER, ActiveArenaPlannerConfig),
        preset_config(EXECUTOR, ActiveArenaPlanConfig),
    )
    assert (planner.type, planner.memory, planner.history, planner.use_state) == (
        "activearena_planner",
        "chunk",
        12,
        False,
    )
    assert (executor.type, executor.memory, executor.think, executor.use_state) == (
        "activearena_plan",
        "planned",
        "none",
        True,
    )
    with pytest.raises(ValueError, match="activearena_plan"):  # an OFT run cannot use the planner's memory
        ActiveArenaOFTConfig(memory="planned", device="cpu")
    with pytest.raises(ValueError, match="lm_loss_weight"):  # the planner's only loss: no weight to set
        ActiveArenaPlannerConfig(lm_loss_weight=0.1, device="cpu")


def test_planner_and_executor_training_inputs(tiny_vlm, bell_count_dataset):
    meta = LeRobotDatasetMetadata(DATASET_REPO, root=bell_count_dataset)
    ann = DatasetAnnotations(bell_count_dataset, DATASET_REPO)
    x, keyframes = ann.subtask_keyframes(FRAME)
    frames = stride_frames(x)

    cfg = ActiveArenaPlannerConfig(vlm_path=str(tiny_vlm), device="cpu")
    torch.manual_seed(0)
    planner = make_policy(cfg, ds_meta=meta)
    pre, _ = make_pre_post_processors(cfg, dataset_stats=meta.stats)
    batch = collate(policy_dataset(cfg, bell_count_dataset, meta), pre, [FRAME])
    assert int(batch[FRAME_VALID][0].sum()) == len(frames) and batch.get("observation.state_token") is None
    seq = planner.assemble(*planner.training_args(batch))
    tok = planner.text_tokenizer
    target = tok.decode(seq["input_ids"][0][seq["kind"][0] == THINK].tolist())
    positions = retrieval_positions(frames, keyframes)
    assert target == planner_target(len(frames), ann.subtask(FRAME), positions) + "<|im_end|>"
    assert positions and keyframes[0] == 0  # the episode's first keyframe window holds its first frame
    prompt = tok.decode(batch[PROMPT_IDS][0][batch[PROMPT_MASK][0]].tolist())
    assert prompt.startswith(planner_prompt(batch["task"][0]))
    loss, info = planner.forward(batch)
    loss.backward()
    assert info["lm_loss"] > 0 and planner.vlm.get_input_embeddings().weight.grad.abs().sum() > 0

    ecfg = ActiveArenaPlanConfig(
        vlm_path=str(tiny_vlm), device="cpu", state_hidden=32, dataset_root=str(bell_count_dataset)
    )
    pre, _ = make_pre_post_processors(ecfg, dataset_stats=meta.stats)
    batch = collate(policy_dataset(ecfg, bell_count_dataset, meta), pre, [FRAME])
    assert int(batch[FRAME_VALID][0].sum()) == len(planned_memory(x, keyframes)) + 1  # retrieved + current
    prompt = tok.decode(batch[PROMPT_IDS][0][batch[PROMPT_MASK][0]].tolist())
    assert prompt.startswith(f'Your task is: "{ann.subtask(FRAME)}"') and "next action" in prompt


def test_an_overfitted_planner_answers_its_target(tiny_vlm, bell_count_dataset):
    """The planner's decode path: after overfitting one sample, its greedy answer parses to the
    sample's subtask and retrieval positions."""
    meta = LeRobotDatasetMetadata(DATASET_REPO, root=bell_count_dataset)
    ann = DatasetAnnotations(bell_count_dataset, DATASET_REPO)
    x, keyframes = ann.subtask_keyframes(FRAME)
    frames = stride_frames(x, history=2)
    cfg = ActiveArenaPlannerConfig(vlm_path=str(tiny_vlm), device="cpu", history=2)
    torch.manual_seed(0)
    planner = make_policy(cfg, ds_meta=meta)
    pre, _ = make_pre_post_processors(cfg, dataset_stats=meta.stats)
    batch = collate(policy_dataset(cfg, bell_count_dataset, meta), pre, [FRAME])
    opt = torch.optim.AdamW(planner.parameters(), lr=5e-3)
    planner.train()
    for _ in range(200):
        loss, _ = planner.forward(batch)
        opt.zero_grad()
        loss.backward()
        opt.step()
        if loss.item() < 0.03:
            break
    planner.eval()
    args = planner.training_args(batch)[:7]
    answer = parse_planner_answer(planner.plan(args)[0], len(frames))
    assert answer == PlannerAnswer(ann.subtask(FRAME), tuple(retrieval_positions(frames, keyframes)))


def test_the_run_time_loop_chains_planner_bank_and_executor(tiny_vlm, bell_count_dataset, tmp_path):
    meta = LeRobotDatasetMetadata(DATASET_REPO, root=bell_count_dataset)
    torch.manual_seed(0)
    make_policy(
        ActiveArenaPlannerConfig(vlm_path=str(tiny_vlm), device="cpu", plan_max_tokens=8), ds_meta=meta
    ).save_pretrained(tmp_path / "planner")
    cfg = ActiveArenaPlanConfig(
        vlm_path=str(tiny_vlm), device="cpu", state_hidden=32, planner_path=str(tmp_path / "planner")
    )
    policy = make_policy(cfg, ds_meta=meta).eval()
    pre, _ = make_pre_post_processors(cfg, dataset_stats=meta.stats)
    frame = LeRobotDataset(DATASET_REPO, root=bell_count_dataset, video_backend="pyav")[FRAME]
    obs = {k: frame[k][None] for k in ("observation.images.head", "observation.state")}
    obs["task"] = [frame["task"]]
    seen = []
    encode = policy.encode

    def spy(*args, vision_cache=None):
        seen.append((int(args[2][0].sum()), policy.text_tokenizer.decode(args[5][0][args[6][0]].tolist())))
        return encode(*args, vision_cache=vision_cache)

    policy.encode = spy
    policy.reset()
    for _ in range(33):  # chunks at 0, 16, 32
        assert policy.select_action(pre(obs)).shape == (1, 18)
    assert policy.rollout_stats() == [{"planner_calls": 3, "malformed_plans": 3, "bank_frames": 0}]
    assert [n for n, _ in seen] == [1, 1, 1]  # nothing retrieved: the current frame only
    assert all(p.startswith(f'Your task is: "{frame["task"]}"') for _, p in seen)  # no subtask yet

    answers = iter(
        [
            "<think>x</think><subtask>ring the bell</subtask><retrieval>[0]</retrieval>",
            "garbled",
            "<think>x</think><subtask>press it</subtask><retrieval>[1]</retrieval>",
        ]
    )
    policy.planner.plan = lambda args, vision_cache=None: [next(answers)]
    policy.reset()
    seen.clear()
    for _ in range(33):
        policy.select_action(pre(obs))
    assert policy.rollout_stats() == [{"planner_calls": 3, "malformed_plans": 1, "bank_frames": 2}]
    assert [n for n, _ in seen] == [1, 2, 3]  # frame 0 retrieved at t=0 stays; frame 16 joins at t=32
    prompts = [p for _, p in seen]
    assert prompts[0].startswith('Your task is: "ring the bell"') and prompts[1] == prompts[0]  # kept
    assert prompts[2].startswith('Your task is: "press it"')


def test_both_presets_train_and_play_through_both_evaluators(tiny_vlm, bell_count_dataset, tmp_path):
    def train(preset, out, *extra):
        return train_preset(preset, bell_count_dataset, tiny_vlm, out, "--policy.state_hidden=32", *extra)

    planner = train(PLANNER, tmp_path / "planner", "--policy.history=2", "--policy.plan_max_tokens=8")
    executor = train(
        EXECUTOR, tmp_path / "executor", "--policy.history=4", f"--policy.planner_path={planner}"
    )
    assert json.loads((executor / "config.json").read_text())["planner_path"] == str(planner.resolve())
    _, mine = play_both(executor, tmp_path, steps=20)
    stats = mine["policy_stats"]  # chunks at steps 0 and 16; 8 tokens never spell an answer
    assert stats == {"planner_calls": 2, "malformed_plans": 2, "bank_frames": 0}
