"""`activearena_oft` on CPU with a tiny random Qwen3-VL saved to disk and loaded by path: shapes and
gradients, an overfit check, think text cannot reach the actions, no future frames in memory, the
memory bank per write policy, save/load round trip, presets, and LeRobot's training and eval loops."""

import dataclasses
import json
import shutil
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import torch
from helpers.params import COUNT, DATASET_REPO as REPO
from helpers.policy_runs import FIXED, RUNS, build_policy, collate, play_both, train_preset
from lerobot.configs.policies import PreTrainedConfig
from lerobot.configs.types import FeatureType, PolicyFeature
from lerobot.policies.factory import make_pre_post_processors

from lerobot_activearena.annotations.keyframes import motion_keyframes
from lerobot_activearena.cli.eval import main as activearena_eval
from lerobot_activearena.episodes.rollout import run_expert_episode
from lerobot_activearena.policies.activearena_oft.configuration_activearena_oft import ActiveArenaOFTConfig
from lerobot_activearena.policies.activearena_oft.modeling_activearena_oft import ActiveArenaOFTPolicy
from lerobot_activearena.policies.activearena_vla.dataset_annotations import (
    DatasetAnnotations,
    decision_clause,
)
from lerobot_activearena.policies.activearena_vla.modeling_activearena_vla import QUERY, STATE, THINK
from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import (
    PIXELS,
    THINK_IDS,
    THINK_MASK,
)
from lerobot_activearena.policies.activearena_vla.tiny_vlm import make_tiny_vlm

CONFIGS = Path(__file__).resolve().parents[2] / "configs" / "policy"


def _exe(name):
    return shutil.which(name, path=str(Path(sys.executable).parent)) or shutil.which(name)


def _torchrun(args, timeout):
    """``torchrun --nproc_per_node=2 *args``; on a timeout torchrun is stopped with SIGTERM, on which it
    ends its ranks (each runs in a session of its own, so killing torchrun alone would leave them)."""
    cmd = [_exe("torchrun"), "--nproc_per_node=2", *map(str, args)]
    with subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as proc:
        try:
            stdout, stderr = proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            proc.terminate()
            proc.communicate(timeout=60)
            raise
    return subprocess.CompletedProcess(cmd, proc.returncode, stdout, stderr)


@pytest.fixture(scope="module")
def vlm(tiny_vlm):
    return tiny_vlm


@pytest.fixture(scope="module")
def root(bell_count_dataset):
    return bell_count_dataset


def _setup(vlm, root, **overrides):
    cfg = ActiveArenaOFTConfig(vlm_path=str(vlm), device="cpu", state_hidden=32, **overrides)
    return cfg, *build_policy(cfg, root)


def test_forward_backward_shapes_and_gradients(vlm, root):
    cfg, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=4, think="subtask")
    batch = collate(ds, pre, [70, len(ds) - 40])
    assert batch["observation.vlm.frame_valid"].shape == (2, 5)  # 4 stride-16 history frames + the current
    assert len(batch[PIXELS]) == int(batch["observation.vlm.frame_valid"].sum())  # present frames only
    assert batch["observation.state"].shape == (2, 5, 18)
    assert batch[THINK_IDS].shape[0] == 2
    loss, info = policy.forward(batch)
    assert torch.isfinite(loss) and info["l1_loss"] > 0 and info["lm_loss"] > 0
    loss.backward()
    for name in (
        "action_queries",
        "head.inp.1.weight",
        "state_encoder.mlp.0.weight",
        "state_encoder.frame.weight",
    ):
        grad = dict(policy.named_parameters())[name].grad
        assert grad is not None and grad.abs().sum() > 0, name
    assert policy.vlm.get_input_embeddings().weight.grad.abs().sum() > 0  # the LM loss reaches the backbone
    policy.reset()
    with torch.no_grad():
        assert policy.predict_action_chunk(collate(ds, pre, [70])).shape == (1, 16, 18)
    groups = policy.get_optim_params()
    assert [g["lr"] for g in groups] == [1e-5, 1e-4]
    assert sum(p.numel() for g in groups for p in g["params"]) == sum(p.numel() for p in policy.parameters())


def test_mrope_positions_follow_the_token_layout_with_injected_embeddings(vlm, root, monkeypatch):
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="none")
    batch = collate(ds, pre, [60])
    seen = {}
    real = policy.vlm.model.language_model.forward

    def spy(**kwargs):
        seen.update(kwargs)
        return real(**kwargs)

    monkeypatch.setattr(policy.vlm.model.language_model, "forward", spy)
    with torch.no_grad():
        seq = policy.assemble(*_encode_args(batch))
        policy.run_backbone(seq)
    assert torch.equal(seen["position_ids"], seq["position_ids"])  # the decoder gets exactly these
    pos = seq["position_ids"][:, 0]  # (3, L): temporal, height, width rows
    image = seq["mm_token_type_ids"][0].bool()
    assert seen.get("input_ids") is None and seen["inputs_embeds"].shape[1] == pos.shape[1]
    merge = policy.vlm.config.vision_config.spatial_merge_size
    grids = seq["image_grid_thw"]
    n_img = int(batch["observation.vlm.frame_valid"].sum())
    assert len(grids) == n_img == 3  # frames 60-32, 60-16 and 60
    starts = torch.nonzero(image[1:] & ~image[:-1]).flatten() + 1
    prev_end = -1
    for (t, h, w), s in zip(grids.tolist(), starts.tolist(), strict=True):
        n = t * h * w // merge**2
        block = pos[:, s : s + n]
        assert image[s : s + n].all() and (block[0] == block[0, 0]).all()  # one temporal index per image
        assert len(block[1].unique()) == h // merge and len(block[2].unique()) == w // merge
        assert block.min() == pos[:, s - 1].max() + 1 > prev_end  # continues after the preceding text
        prev_end = block.max()
    text = ~image
    text_pos = pos[:, text]
    assert (text_pos[0] == text_pos[1]).all() and (text_pos[1] == text_pos[2]).all()  # text: all rows equal
    assert (text_pos[0].diff() > 0).all()  # and strictly increasing, state and query tokens included


def test_loss_decreases_when_overfitting_a_fixed_batch(vlm, root):
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="instruction")
    batch = collate(ds, pre, [20, 90, len(ds) - 30])
    opt = torch.optim.AdamW(policy.parameters(), lr=1e-3)
    losses = []
    for _ in range(30):
        loss, info = policy.forward(batch)
        opt.zero_grad()
        loss.backward()
        opt.step()
        losses.append(info["l1_loss"])
    assert losses[-1] < 0.5 * losses[0], losses


def test_actions_cannot_see_the_think_text(vlm, root):
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="subtask")
    batch = collate(ds, pre, [40, len(ds) - 10])
    policy.eval()
    with torch.no_grad():
        a_none, _ = policy.encode(*_encode_args(batch))
        a_think, lm = policy.encode(*_encode_args(batch), batch[THINK_IDS], batch[THINK_MASK])
        other = torch.flip(batch[THINK_IDS], dims=[1])
        a_other, lm_other = policy.encode(
            *_encode_args(batch), other, torch.flip(batch[THINK_MASK], dims=[1])
        )
    assert torch.allclose(a_none, a_think, atol=1e-5) and torch.allclose(a_none, a_other, atol=1e-5)
    assert not torch.isclose(lm, lm_other)  # the think span is really there and read by the LM loss


def _memorise(policy, batch, steps: int = 150) -> None:
    """Fit the policy to this one batch (its subtask text and chunk), then switch it to evaluation."""
    opt = torch.optim.AdamW(policy.parameters(), lr=3e-3)
    for _ in range(steps):
        loss, _ = policy.forward(batch)
        opt.zero_grad()
        loss.backward()
        opt.step()
    policy.eval()


def test_think_first_actions_read_the_think_text(vlm, root):
    """``think_first``: the span sits between the prompt and the queries, so the actions change with it."""
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="subtask", think_first=True)
    batch = collate(ds, pre, [40, len(ds) - 10])
    policy.eval()
    with torch.no_grad():
        seq = policy.assemble(*_encode_args(batch), batch[THINK_IDS], batch[THINK_MASK])
        a_think, lm = policy.encode(*_encode_args(batch), batch[THINK_IDS], batch[THINK_MASK])
        other = torch.flip(batch[THINK_IDS], dims=[1])
        a_other, lm_other = policy.encode(
            *_encode_args(batch), other, torch.flip(batch[THINK_MASK], dims=[1])
        )
    for kind in seq["kind"]:
        think_at, query_at = torch.nonzero(kind == 4).flatten(), torch.nonzero(kind == 3).flatten()
        assert think_at.max() < query_at.min() and len(query_at) == 16
    assert (a_think - a_other).abs().max() > 1e-4
    assert not torch.isclose(lm, lm_other)


def test_think_first_decodes_its_span_then_acts_on_it(vlm, root):
    _, policy, pre, _, ds = _setup(
        vlm, root, memory="chunk", history=4, think="subtask", think_first=True, subtask_max_tokens=24
    )
    batch = collate(ds, pre, [len(ds) - 20])
    _memorise(policy, batch)
    target = batch[THINK_IDS][0][batch[THINK_MASK][0]].tolist()  # <think> text </think> <|im_end|>
    with torch.no_grad():
        tokens, chunk = policy.think_then_act(_encode_args(batch))
        taught, _ = policy.encode(*_encode_args(batch), batch[THINK_IDS], batch[THINK_MASK])
        cached = policy.greedy_decode(_encode_args(batch), target[:1], target[-2], 6, use_cache=True)
        full = policy.greedy_decode(_encode_args(batch), target[:1], target[-2], 6, use_cache=False)
        blank_think = torch.full_like(batch[THINK_IDS], policy.pad_id)
        untaught, _ = policy.encode(*_encode_args(batch), blank_think, batch[THINK_MASK])
        predicted = policy.predict_action_chunk(batch)  # a dataset batch: decodes too
    assert list(tokens[0]) == target[1:-1]
    assert torch.allclose(chunk, taught, atol=1e-5) and torch.allclose(predicted, taught, atol=1e-5)
    assert (untaught - taught).abs().max() > 1e-3  # the chunk depends on the span it decoded
    assert cached[0] == full[0]  # decoding leaves the queries out, so the cache sees what training did
    for a, b in zip(cached[1], full[1], strict=True):
        assert torch.allclose(a, b, atol=1e-4), (a - b).abs().max()


def test_think_first_settings_that_cannot_work_are_named(vlm):
    with pytest.raises(ValueError, match="needs a think target"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), think="none", think_first=True)
    with pytest.raises(ValueError, match="does not combine with memory=subtask"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), memory="subtask", think="subtask", think_first=True)


def test_memory_state_frames_give_the_memory_its_poses_and_the_current_frame_none(vlm, root):
    """``state_frames=memory``: a state token after every memory frame and none after the current one,
    so the chunk follows a memory frame's state and not the current state."""
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=4, state_frames="memory")
    _, every, _, _, _ = _setup(vlm, root, memory="chunk", history=4)
    every.load_state_dict(policy.state_dict())
    batch = collate(ds, pre, [len(ds) - 10])
    policy.eval(), every.eval()
    n_memory = int(batch["observation.vlm.frame_valid"][0, :-1].sum())
    assert n_memory >= 2
    seq = policy.assemble(*_encode_args(batch))
    assert int((seq["kind"] == STATE).sum()) == n_memory  # none after the current frame
    assert int((every.assemble(*_encode_args(batch))["kind"] == STATE).sum()) == n_memory + 1

    def chunk(model, state):
        with torch.no_grad():
            return model.encode(*_encode_args({**batch, "observation.state": state}))[0]

    state = batch["observation.state"]
    moved_now, moved_memory = state.clone(), state.clone()
    moved_now[:, -1] += 0.5
    moved_memory[:, -2] += 0.5
    assert torch.equal(chunk(policy, moved_now), chunk(policy, state))
    assert not torch.allclose(chunk(policy, moved_memory), chunk(policy, state))
    assert not torch.allclose(chunk(every, moved_now), chunk(every, state))


def test_memory_state_dropout_shows_the_current_state_on_the_memory_frames_in_training_only(vlm, root):
    """memory_state_dropout=1: in training every memory frame's state token reads the current state (the
    loss of a batch whose memory states are set so); 0 keeps their own; evaluation always reads them."""
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=4, memory_state_dropout=1.0)
    batch = collate(ds, pre, [len(ds) - 10, 70])
    assert int(batch["observation.vlm.frame_valid"][0, :-1].sum()) >= 2
    state = batch["observation.state"]
    flat = {**batch, "observation.state": state[:, -1:].expand_as(state).clone()}
    policy.train()
    dropped = policy.forward(dict(batch))[0]
    policy.config.memory_state_dropout = 0.0
    assert torch.allclose(dropped, policy.forward(dict(flat))[0], atol=1e-6)
    assert not torch.allclose(dropped, policy.forward(dict(batch))[0], atol=1e-4)
    policy.config.memory_state_dropout = 1.0
    policy.eval()
    with torch.no_grad():
        assert not torch.allclose(policy.forward(dict(batch))[0], policy.forward(dict(flat))[0], atol=1e-4)
    with pytest.raises(ValueError, match="memory_state_dropout"):
        ActiveArenaOFTConfig(memory="none", history=0, memory_state_dropout=0.5, device="cpu")
    with pytest.raises(ValueError, match="probability"):
        ActiveArenaOFTConfig(memory_state_dropout=1.5, device="cpu")


def _encode_args(batch):
    return (
        batch[PIXELS],
        batch["observation.vlm.image_grid_thw"],
        batch["observation.vlm.frame_valid"],
        batch["observation.state"],
        batch["observation.vlm.prefix_ids"],
        batch["observation.vlm.prompt_ids"],
        batch["observation.vlm.prompt_mask"],
    )


def test_keyframe_memory_never_reads_the_future(vlm, root):
    ann = DatasetAnnotations(root, REPO)
    for policy in ("chunk", "subtask", "motion"):
        for i in range(len(ann.cols["episode_index"])):
            mem = ann.memory_indices(i, policy, 12)
            ep = ann.cols["episode_index"][i]
            assert all(m < i and ann.cols["episode_index"][m] == ep for m in mem), (policy, i, mem)
            assert len(mem) <= 12
    # a training batch with motion memory: history slots hold exactly the retained past frames
    cfg, policy, pre, _, ds = _setup(vlm, root, memory="motion", history=3, think="none")
    t = len(ds) - 60
    batch = collate(ds, pre, [t])
    mem = ann.memory_indices(t, "motion", 3)
    assert batch["observation.vlm.frame_valid"][0].tolist() == [False] * (3 - len(mem)) + [True] * (
        len(mem) + 1
    )
    raw = batch["observation.vlm.raw_state"][0, 3 - len(mem) :]
    expect = torch.stack([ds.hf_dataset[m]["observation.state"] for m in mem + [t]])
    assert torch.allclose(raw, expect)


def _scripted_observations(n_steps, seed=0):
    """An expert trajectory's states with small random images, as lerobot-eval would pass them."""
    ref = run_expert_episode(COUNT, 0, "id")
    gen = torch.Generator().manual_seed(seed)
    for t in range(n_steps):
        yield (
            t,
            {
                "observation.images.head": torch.rand(1, 3, 64, 64, generator=gen),
                "observation.state": torch.as_tensor(ref.states[t], dtype=torch.float32)[None],
                "task": [ref.sidecar["instruction"]],
            },
            ref.states,
        )


@pytest.mark.parametrize("memory", ["chunk", "motion", "none"])
def test_memory_bank_contents_per_write_policy(vlm, root, memory):
    _, policy, pre, _, _ = _setup(vlm, root, memory=memory, history=4, think="none")
    n_steps = 70
    observations = list(_scripted_observations(n_steps))
    states = observations[0][2]  # the reference trajectory's states (the same in every item)
    for t, obs, _ in observations:
        batch = pre(obs)
        assert all(e["t"] < t for e in policy.memory(0))  # only the past is memory
        policy.select_action(batch)
        assert policy.step == t + 1
        if policy.memory(0) and policy.memory(0)[-1]["t"] == t:  # written now: it is this step's frame
            assert torch.equal(policy.memory(0)[-1]["pixels"], batch[PIXELS][0])
    if memory == "chunk":
        expected = [0, 16, 32, 48, 64]
    elif memory == "motion":
        expected = [int(i) for i in np.flatnonzero(motion_keyframes(states[:n_steps]))]
    else:
        expected = []
    assert [e["t"] for e in policy.memory(0)] == expected[-4:]
    assert policy.queued_actions == 16 - n_steps % 16  # whole 16-step chunks, one popped per step
    policy.reset()
    assert policy.memory(0) == [] and policy.queued_actions == 0 and policy.step == 0


@pytest.mark.parametrize("n_action_steps", [8, 5])
def test_chunk_memory_re_planning_within_a_chunk_reads_the_training_history(vlm, root, n_action_steps):
    """Re-planning every n < 16 steps, each decision at step t reads the frames t-16, t-32, ... (the K
    newest), the history every training frame t has (``memory_frames("chunk", t, K)``), never a frame
    1-15 steps old; the bank keeps the frames later decisions read."""
    from lerobot_activearena.annotations.keyframes import memory_frames

    _, policy, pre, _, _ = _setup(
        vlm, root, memory="chunk", history=3, think="none", n_action_steps=n_action_steps
    )
    read, real = {}, policy.chunk_memory

    def spy(b):
        entries = real(b)
        read[policy.step] = [e["t"] for e in entries]
        return entries

    policy.chunk_memory = spy
    for t, obs, _ in _scripted_observations(70):
        batch = pre(obs)
        policy.select_action(batch)
        if t % n_action_steps == 0:
            assert read[t] == memory_frames("chunk", t, 3), t
    assert sorted(read) == list(range(0, 70, n_action_steps))  # a decision every n steps, no other
    assert any(len(m) == 3 for m in read.values())
    stride = 8 if n_action_steps == 8 else 1
    assert all(e["t"] % stride == 0 for e in policy.memory(0))
    assert [e["t"] for e in policy.memory(0)][-1] == 69 // stride * stride


@pytest.mark.parametrize("memory", ["chunk", "motion"])
def test_env_frames_become_pixels_only_where_the_policy_reads_them(vlm, root, memory, monkeypatch):
    """The preprocessor hands an env step's frames over as uint8; the policy runs the image processor only
    at chunk boundaries and memory writes, and acts exactly as when every step is processed."""
    from lerobot_activearena.policies.activearena_vla import modeling_activearena_vla as modeling
    from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import (
        FRAMES,
        ActiveArenaVLMInputsStep,
        EnvFrames,
    )

    # motion memory writes off the chunk grid; chunk memory re-plans at its writes (n_action_steps 16)
    n_action_steps = 16 if memory == "chunk" else 8
    _, policy, pre, _, _ = _setup(
        vlm, root, memory=memory, history=4, think="none", n_action_steps=n_action_steps
    )
    step = next(s for s in pre.steps if isinstance(s, ActiveArenaVLMInputsStep))
    processed, real = [], modeling.frame_inputs
    monkeypatch.setattr(
        modeling, "frame_inputs", lambda *a, **k: processed.append(policy.step) or real(*a, **k)
    )
    runs = {}
    for defer in (True, False):
        step.defer_env_frames = defer
        policy.reset()
        actions = []
        for _t, obs, _ in _scripted_observations(50):
            batch = pre(obs)
            assert (FRAMES in batch) == defer and (PIXELS in batch) != defer
            assert not defer or isinstance(batch[FRAMES], EnvFrames)  # not a tensor: not copied to the device
            actions.append(policy.select_action(batch))
        runs[defer] = torch.stack(actions), [(e["t"], e["pixels"]) for e in policy.memory(0)]
    (deferred, bank), (eager, eager_bank) = runs[True], runs[False]
    assert torch.equal(deferred, eager)
    assert [t for t, _ in bank] == [t for t, _ in eager_bank] and len(bank) > 1
    assert all(torch.equal(a, b) for (_, a), (_, b) in zip(bank, eager_bank, strict=True))
    chunk_starts = set(range(0, 50, n_action_steps))
    writes = {0, 16, 32, 48} if memory == "chunk" else set(range(50)) - chunk_starts
    assert chunk_starts <= set(processed)  # every chunk boundary processed its frame once
    assert len(processed) == len(set(processed)) < 50
    if memory == "chunk":
        assert set(processed) == chunk_starts  # the writes (every 16th step) fall on chunk boundaries
    else:
        assert set(processed) - chunk_starts <= writes and {t for t, _ in bank} <= set(processed)


def test_the_current_frame_at_more_tokens_keeps_the_memory_at_its_own_size(vlm, root, monkeypatch):
    """current_image_pixels at evaluation: each decision reads the current frame at that size (4x the
    memory frames' tokens here), the memory bank keeps the frames at image_max_pixels (a table policy's
    memory tower reads them as it was trained), and the same observations give the same actions."""
    from lerobot_activearena.policies.activearena_vla import modeling_activearena_vla as modeling

    memory_pixels = 32 * 32 * 4  # the scripted 64 x 64 frames read at 2 x 2 tokens
    _, policy, pre, _, _ = _setup(
        vlm, root, memory="chunk", history=2, think="none", image_max_pixels=memory_pixels,
        current_image_pixels=4 * memory_pixels,
    )  # fmt: skip
    seen = []
    real = modeling.ActiveArenaVLAPolicy.assemble
    monkeypatch.setattr(
        modeling.ActiveArenaVLAPolicy,
        "assemble",
        lambda self, pixels, grid, valid, *a, **k: (
            seen.append((pixels.shape, grid, valid)) or real(self, pixels, grid, valid, *a, **k)
        ),
    )
    runs = []
    for _ in range(2):
        policy.reset()
        actions = [policy.select_action(pre(obs)) for _t, obs, _ in _scripted_observations(40)]
        runs.append((torch.stack(actions), policy.memory(0)))
    assert torch.equal(runs[0][0], runs[1][0])
    bank = runs[0][1]
    assert [e["t"] for e in bank] == [16, 32] and all(int(e["grid"].prod()) == 16 for e in bank)
    assert all(e["pixels"].shape[0] == 16 for e in bank)
    for shape, grid, valid in seen[:3]:  # the decisions at steps 0, 16 and 32 of the first run
        patches = grid[valid].prod(-1).tolist()
        assert patches[-1] == 64 and all(n == 16 for n in patches[:-1])
        assert shape[0] == sum(patches) if len(shape) == 2 else shape[0] * shape[1] == sum(patches)
    assert [int(v.sum()) for _, _, v in seen[:3]] == [1, 2, 3]


def test_subtask_memory_writes_where_the_predicted_subtask_changes(vlm, root, monkeypatch):
    _, policy, pre, _, _ = _setup(vlm, root, memory="subtask", history=4, think="subtask")
    script = {0: (5, 6), 16: (5, 6), 32: (7,), 48: (8, 9), 64: (8, 9)}  # predicted subtask per chunk boundary
    monkeypatch.setattr(
        policy,
        "predict_subtask_and_actions",
        lambda args, vision_cache=None: ([script[policy.step]], policy.encode(*args)[0]),
    )
    for _t, obs, _ in _scripted_observations(70):
        policy.select_action(pre(obs))
    assert [e["t"] for e in policy.memory(0)] == [0, 32, 48]
    _, refused, pre2, _, _ = _setup(vlm, root, memory="subtask", history=4, think="none")
    _, obs, _ = next(_scripted_observations(1))
    with pytest.raises(ValueError, match="think=subtask"):
        refused.select_action(pre2(obs))


def test_subtask_memory_decodes_and_acts_from_one_pass(vlm, root):
    _, policy, pre, _, _ = _setup(
        vlm, root, memory="subtask", history=4, think="subtask", subtask_max_tokens=4
    )
    policy.eval()
    _, obs, _ = next(_scripted_observations(1))
    batch = pre(obs)
    policy.start_episode(batch)
    pixels, grid, valid, state, _ = policy.history_batch(batch)
    with torch.no_grad():
        alone, _ = policy.encode(
            pixels,
            grid,
            valid,
            state,
            batch["observation.vlm.prefix_ids"],
            batch["observation.vlm.prompt_ids"],
            batch["observation.vlm.prompt_mask"],
        )
    action = policy.select_action(batch)
    assert torch.allclose(action, alone[:, 0], atol=1e-5)
    assert policy.predicted_subtask(0) is not None and len(policy.predicted_subtask(0)) <= 4  # within budget
    assert [e["t"] for e in policy.memory(0)] == [0]  # the first predicted subtask starts the memory


def test_a_wrongly_shaped_state_at_evaluation_is_named(vlm, root):
    _, policy, pre, _, _ = _setup(vlm, root, memory="motion", history=4, think="none")
    _, obs, _ = next(_scripted_observations(1))
    obs["observation.state"] = obs["observation.state"][:, :1]  # e.g. one joint instead of the 18-D state
    with pytest.raises(ValueError, match=r"observation.state must be \(batch, 18\)"):
        policy.select_action(pre(obs))


def test_backbone_matches_qwen3_vl_forward(vlm, root):
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=4, think="none")
    batch = collate(ds, pre, [20, len(ds) - 40])
    with torch.no_grad():
        seq = policy.assemble(*_encode_args(batch))
        ours = policy.run_backbone(seq)[0].last_hidden_state
        keys = (
            "inputs_embeds",
            "attention_mask",
            "position_ids",
            "pixel_values",
            "image_grid_thw",
            "mm_token_type_ids",
        )
        ref = policy.vlm.model(input_ids=None, **{k: seq[k] for k in keys}).last_hidden_state
    real = seq["attention_mask"].bool()
    assert not real.all()  # padded: ours runs without the padding mask (causal only), the reference with it
    assert torch.allclose(ours[real], ref[real], atol=1e-5)


def test_memory_frames_are_encoded_once_and_reused(vlm, root, monkeypatch):
    _, policy, pre, _, _ = _setup(vlm, root, memory="chunk", history=2, think="none")
    policy.eval()
    seen = []
    vision = policy.vision_features
    monkeypatch.setattr(
        policy, "vision_features", lambda pv, grid, *a: seen.append(len(grid)) or vision(pv, grid, *a)
    )
    for t, obs, _ in _scripted_observations(33):
        batch = pre(obs)
        if t == 32:  # a full bank (frames 0 and 16): compare with encoding every image afresh
            pixels, grid, valid, state, _ = policy.history_batch(batch)
            with torch.no_grad():
                fresh, _ = policy.encode(
                    pixels,
                    grid,
                    valid,
                    state,
                    batch["observation.vlm.prefix_ids"],
                    batch["observation.vlm.prompt_ids"],
                    batch["observation.vlm.prompt_mask"],
                )
            seen.clear()
        action = policy.select_action(batch)
    assert seen == [1]  # only the current frame went through the vision tower
    assert torch.allclose(action, fresh[:, 0], atol=1e-5)
    assert all(e["vision"] is not None for e in policy.memory(0))


def test_greedy_think_decoding_recovers_a_learned_subtask(vlm, root):
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=0, think="subtask")
    batch = collate(ds, pre, [len(ds) - 20])
    _memorise(policy, batch)
    decoded = policy.predict_subtask(_encode_args(batch))[0]
    target = batch[THINK_IDS][0][batch[THINK_MASK][0]].tolist()  # <think> text </think> <|im_end|>
    assert list(decoded) == target[1:-1]


def test_cached_think_decoding_matches_re_encoding_the_whole_sequence(vlm, root):
    _, policy, pre, _, ds = _setup(
        vlm, root, memory="chunk", history=4, think="subtask", subtask_max_tokens=6
    )
    batch = collate(ds, pre, [20, len(ds) - 40])  # 2 and 5 valid frames: sequences of different lengths
    assert batch["observation.vlm.frame_valid"].sum(1).tolist() == [2, 5]
    policy.eval()
    with torch.no_grad():
        cached, cached_logits, actions = policy.greedy_think(_encode_args(batch), use_cache=True)
        full, full_logits, _ = policy.greedy_think(_encode_args(batch), use_cache=False)
        alone, _ = policy.encode(*_encode_args(batch))
    assert cached == full and len(cached_logits) == len(full_logits) == 6
    assert torch.allclose(actions, alone, atol=1e-5)  # one pass serves the chunk and the subtask
    for a, b in zip(cached_logits, full_logits, strict=True):
        assert torch.allclose(a, b, atol=1e-4), (a - b).abs().max()


def test_save_and_reload_give_identical_actions(vlm, root, tmp_path):
    cfg, policy, pre, post, ds = _setup(vlm, root, memory="chunk", history=2, think="subtask")
    with torch.no_grad():
        for p in policy.head.parameters():
            p.add_(0.01 * torch.randn_like(p))  # not the init: the weights must really round-trip
    policy.save_pretrained(tmp_path)
    pre.save_pretrained(tmp_path)
    post.save_pretrained(tmp_path)
    loaded = ActiveArenaOFTPolicy.from_pretrained(tmp_path)
    pre2, post2 = make_pre_post_processors(loaded.config, pretrained_path=str(tmp_path))
    policy.eval()
    loaded.eval()
    raw = torch.utils.data.default_collate([ds[50]])
    with torch.no_grad():
        a = post(policy.predict_action_chunk(pre(dict(raw))))
        b = post2(loaded.predict_action_chunk(pre2(dict(raw))))
    assert torch.equal(a, b)
    # a fine-tune whose command line changes the annotation is refused: the saved preprocessor would win
    changed = dataclasses.replace(loaded.config, think="none", decision_weight=5.0)
    with pytest.raises(
        ValueError, match=r"think='none' \(saved: 'subtask'\), decision_weight=5.0 \(saved: 1.0\)"
    ):
        ActiveArenaOFTPolicy.from_pretrained(tmp_path, config=changed)
    bigger = dataclasses.replace(loaded.config, current_image_pixels=4 * loaded.config.image_max_pixels)
    with pytest.raises(ValueError, match=r"current_image_pixels=\d+ \(saved: None\)"):
        ActiveArenaOFTPolicy.from_pretrained(tmp_path, config=bigger)


def test_bad_config_values_are_named():
    with pytest.raises(ValueError, match="memory"):
        ActiveArenaOFTConfig(memory="planned", device="cpu")
    with pytest.raises(ValueError, match="think"):
        ActiveArenaOFTConfig(think="plan", device="cpu")
    with pytest.raises(ValueError, match="n_action_steps"):
        ActiveArenaOFTConfig(n_action_steps=20, device="cpu")
    # chunk memory re-plans off its 16-step grid too (test_chunk_memory_re_planning_...)
    assert (
        ActiveArenaOFTConfig(memory="chunk", history=12, n_action_steps=8, device="cpu").n_action_steps == 8
    )
    assert ActiveArenaOFTConfig(memory="none", n_action_steps=8, device="cpu").n_action_steps == 8
    with pytest.raises(ValueError, match="attn_implementation must be one of .*sdpa"):
        ActiveArenaOFTConfig(attn_implementation="flash3", device="cpu")
    with pytest.raises(ValueError, match="memory_ablation must be one of"):
        ActiveArenaOFTConfig(memory_ablation="noise", device="cpu")
    with pytest.raises(ValueError, match="memory_ablation=blank .* this policy has no memory"):
        ActiveArenaOFTConfig(memory="none", memory_ablation="blank", device="cpu")
    with pytest.raises(ValueError, match="memory_vision must be one of"):
        ActiveArenaOFTConfig(memory_vision="copy", device="cpu")
    with pytest.raises(ValueError, match="memory_vision=frozen .* needs a memory"):
        ActiveArenaOFTConfig(memory="none", memory_vision="frozen", device="cpu")
    with pytest.raises(ValueError, match="memory_vision=frozen .*freeze_vision=false .*freeze_vision=True"):
        ActiveArenaOFTConfig(memory_vision="frozen", freeze_vision=True, device="cpu")
    with pytest.raises(ValueError, match="state_frames must be all or memory"):
        ActiveArenaOFTConfig(state_frames="current", device="cpu")
    with pytest.raises(ValueError, match="state_frames=memory .* needs use_state=true and a memory"):
        ActiveArenaOFTConfig(memory="none", state_frames="memory", device="cpu")
    with pytest.raises(ValueError, match="state_frames=memory .*use_state=False"):
        ActiveArenaOFTConfig(use_state=False, state_frames="memory", device="cpu")
    with pytest.raises(ValueError, match="vision_lr is .*freeze_vision=false"):
        ActiveArenaOFTConfig(vision_lr=1e-4, freeze_vision=True, device="cpu")


def test_local_vlm_and_dataset_paths_are_stored_absolute(vlm, tmp_path, monkeypatch):
    monkeypatch.chdir(vlm.parent)
    cfg = ActiveArenaOFTConfig(vlm_path=vlm.name, dataset_root=".", device="cpu")
    assert cfg.vlm_path == str(vlm.resolve()) and cfg.dataset_root == str(vlm.parent.resolve())
    monkeypatch.chdir(
        tmp_path
    )  # e.g. lerobot-eval started elsewhere: the saved config still points at the VLM
    cfg.save_pretrained(tmp_path / "ckpt")
    reloaded = ActiveArenaOFTConfig.from_pretrained(tmp_path / "ckpt")
    assert reloaded.vlm_path == str(vlm.resolve())
    assert (
        ActiveArenaOFTConfig(device="cpu").vlm_path == "Qwen/Qwen3-VL-2B-Instruct"
    )  # a Hub id stays as it is


def test_a_missing_vlm_names_the_flag_and_the_fix(tmp_path):
    cfg = ActiveArenaOFTConfig(vlm_path=str(tmp_path / "no_such_vlm"), device="cpu")
    with pytest.raises(OSError, match="--policy.vlm_path") as err:
        make_pre_post_processors(cfg, dataset_stats={})
    assert "activearena-make-tiny-vlm" in str(err.value) and "processor" in str(err.value)
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(OSError, match="Qwen3-VL model from vlm_path"):
        ActiveArenaOFTPolicy(
            ActiveArenaOFTConfig(
                vlm_path=str(empty),
                device="cpu",
                input_features={
                    "observation.images.head": PolicyFeature(FeatureType.VISUAL, (3, 384, 512)),
                    "observation.state": PolicyFeature(FeatureType.STATE, (18,)),
                },
                output_features={"action": PolicyFeature(FeatureType.ACTION, (18,))},
            )
        )


def test_the_2b_architecture_preset_has_the_real_models_size(tmp_path):
    from transformers import Qwen3VLForConditionalGeneration

    from lerobot_activearena.policies.activearena_oft.heads import MLPResNet
    from lerobot_activearena.policies.activearena_vla.tiny_vlm import QWEN3_VL_2B, qwen3_vl_config

    cfg = qwen3_vl_config(QWEN3_VL_2B["text"], QWEN3_VL_2B["vision"])
    with torch.device("meta"):  # shapes only, no memory
        model = Qwen3VLForConditionalGeneration(cfg)
        head = MLPResNet(cfg.text_config.hidden_size, 2 * cfg.text_config.hidden_size, 18, 2)
    assert 2.0e9 < sum(p.numel() for p in model.parameters()) < 2.2e9
    assert (head.inp[1].in_features, head.inp[1].out_features) == (2048, 4096)  # the paper's OFT head
    with pytest.raises(ValueError, match="architecture"):
        make_tiny_vlm(tmp_path / "x", architecture="qwen3-vl-8b")


def test_presets_match_the_papers_run_names():
    names = sorted(p.stem for p in CONFIGS.glob("oft_*.json") if "_planned_" not in p.stem)  # Plan: own types
    assert names == sorted([r for r in RUNS if r.startswith("oft_") and "_planned_" not in r] + [FIXED])
    memory_of = {"action": "chunk", "no": "none", "motion": "motion", "subtask": "subtask"}
    for name in names:
        _, think, history, k, state, *fixed = name.split("_")
        policy = json.loads((CONFIGS / f"{name}.json").read_text())["policy"]
        cfg = ActiveArenaOFTConfig(**{k2: v for k2, v in policy.items() if k2 != "type"}, device="cpu")
        assert cfg.fixed_view == (fixed == ["fixed"])
        assert cfg.think == {"no": "none"}.get(think, think) and cfg.memory == memory_of[history]
        assert cfg.history == int(k) and cfg.use_state == (state == "ws")
        expected = [-16 * i for i in range(int(k), 0, -1)] + [0] if history == "action" else None
        assert cfg.observation_delta_indices == expected
        # the paper's batch 7 at K=12 fits an 80 GB GPU only with activation checkpointing (issue figures:
        # 50.5 GiB with it, out of memory without), over float32 master weights
        assert cfg.gradient_checkpointing and cfg.weights_dtype == "float32" and cfg.dtype == "auto"


def test_lerobot_train_then_lerobot_eval(vlm, root, tmp_path):
    """A preset from configs/policy through LeRobot's training loop (as ``lerobot-train
    --config_path``; the CLIs' own discovery of the type is test_plugin_discovery's), then its
    checkpoint through LeRobot's eval loop and through activearena-eval: the same episode."""
    train_dir = tmp_path / "train"
    ckpt = train_preset(
        CONFIGS / "oft_subtask_action_6_ws.json", root, vlm, train_dir, "--policy.state_hidden=32"
    )
    assert json.loads((ckpt / "config.json").read_text())["history"] == 6
    assert (train_dir / "checkpoints" / "last" / "training_state" / "training_step.json").exists()
    # the same checkpoint through LeRobot's eval loop and activearena-eval's shards: the same episode
    theirs, mine = play_both(ckpt, tmp_path, steps=32)
    assert list((tmp_path / "lerobot_eval").glob("videos/*/*.mp4"))
    for key in ("failure_state", "view_targets"):
        assert mine[key] == theirs[key], key


def test_the_fixed_preset_learns_the_arms_and_holds_the_view_at_home(vlm, root, tmp_path):
    """ActiveArena-Fixed: the OFT head regresses the 16 arm and gripper dimensions only; every action
    the checkpoint's postprocessor returns has the torso yaw and head pitch at home, and it plays
    through activearena-eval with the fixed-view env config."""
    from lerobot_activearena.sim.embodiment import HOME_HEAD_PITCH, HOME_TORSO_YAW

    ckpt = train_preset(
        CONFIGS / "oft_subtask_action_12_ws_fixed.json",
        root,
        vlm,
        tmp_path / "train",
        "--policy.state_hidden=32",
        "--policy.history=2",
    )
    policy_cfg = PreTrainedConfig.from_pretrained(ckpt)
    assert policy_cfg.fixed_view and policy_cfg.predicted_action_dim == 16
    policy = ActiveArenaOFTPolicy.from_pretrained(ckpt, config=policy_cfg)
    assert policy.head.out[-1].out_features == 16
    _, post = make_pre_post_processors(policy_cfg, pretrained_path=str(ckpt))
    actions = post(torch.randn(3, 18))
    assert actions.shape == (3, 18) and not torch.equal(actions[:, :16], torch.zeros(3, 16))
    assert (actions[:, 16] == HOME_TORSO_YAW).all() and (actions[:, 17] == HOME_HEAD_PITCH).all()

    run = tmp_path / "protocol"
    activearena_eval(
        [
            f"--config_path={CONFIGS.parent / 'env' / 'activearena_fixed_id.json'}",
            f"--policy.path={ckpt}",
            "--policy.device=cpu",
            "--tasks=click_bell_rotate_view",
            "--env.episode_length=16",
            "--episodes=1",
            "--videos=0",
            f"--out={run}",
        ]
    )
    record = json.loads((run / "id" / "episodes" / "records.jsonl").read_text().splitlines()[0])
    assert record["steps"] == 16
    np.testing.assert_allclose(np.asarray(record["view_targets"], float).reshape(-1, 2), [[0.0, 1.0]] * 16)


def _changed_fraction(vlm, root, **precision):
    """Fraction of backbone weights that one AdamW step at the paper's lr (1e-5) changes: Adam's first
    step moves every weight with a gradient by about lr, so later steps change no more weights (on a
    CPU without native bfloat16 each step takes ~10 s)."""
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="none", **precision)
    policy.train()
    batch = collate(ds, pre, [20])
    before = [p.detach().clone() for p in policy.vlm.parameters()]
    opt = torch.optim.AdamW(policy.get_optim_params(), betas=(0.9, 0.95), eps=1e-8, weight_decay=1e-8)
    loss, _ = policy.forward(batch)
    loss.backward()
    opt.step()
    changed = sum(int((p.detach() != b).sum()) for p, b in zip(policy.vlm.parameters(), before, strict=True))
    return changed / sum(b.numel() for b in before), policy


def test_bfloat16_compute_keeps_float32_master_weights_so_small_updates_apply(vlm, root):
    """bfloat16 autocast (the CUDA default) over float32 weights applies lr-1e-5 updates; pure bfloat16
    weights (only by an explicit flag, with a warning) round most of them away."""
    mixed, policy = _changed_fraction(vlm, root, dtype="bfloat16")
    assert policy.config.autocast_bfloat16 and next(policy.vlm.parameters()).dtype == torch.float32
    with pytest.warns(UserWarning, match="weights_dtype=bfloat16"):
        pure, policy = _changed_fraction(vlm, root, dtype="bfloat16", weights_dtype="bfloat16")
    assert next(policy.vlm.parameters()).dtype == torch.bfloat16
    assert mixed > 0.9 and pure < 0.5 * mixed, (mixed, pure)


def _loss_and_grads(vlm, root, **checkpointing):
    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="subtask", **checkpointing)
    policy.train()
    loss, _ = policy.forward(collate(ds, pre, [20, len(ds) - 40]))
    loss.backward()
    flags = {
        n: m.gradient_checkpointing
        for n, m in policy.vlm.named_modules()
        if n.endswith("blocks.0") or n.rsplit(".", 1)[0].endswith("language_model.layers")
    }
    return (
        policy,
        float(loss.detach()),
        {n: p.grad for n, p in policy.named_parameters() if p.grad is not None},
        flags,
    )


def _assert_same_step(loss, grads, other_loss, other_grads, rel, atol, rtol):
    """The same loss (within ``rel``) and the same gradient for every parameter."""
    assert other_loss == pytest.approx(loss, rel=rel)
    assert other_grads.keys() == grads.keys()
    for name, g in grads.items():
        assert torch.allclose(other_grads[name], g, atol=atol, rtol=rtol), name


@pytest.mark.parametrize(
    "layers,mode", [("all", "full"), ("vision", "full"), ("language", "full"), ("all", "selective")]
)
def test_gradient_checkpointing_of_some_layers_gives_the_same_gradients(vlm, root, layers, mode):
    """gradient_checkpointing_layers picks the blocks that recompute (vision tower, language model or
    both), in full or selectively; the loss and every gradient equal those of the step without
    checkpointing."""
    _, loss, grads, flags = _loss_and_grads(vlm, root)
    assert not any(flags.values())
    _, ck_loss, ck_grads, ck_flags = _loss_and_grads(
        vlm,
        root,
        gradient_checkpointing=True,
        gradient_checkpointing_layers=layers,
        gradient_checkpointing_mode=mode,
    )
    vision = ck_flags["model.visual.blocks.0"]
    language = ck_flags["model.language_model.layers.0"]
    assert (vision, language) == {"all": (True, True), "vision": (True, False), "language": (False, True)}[
        layers
    ]
    _assert_same_step(loss, grads, ck_loss, ck_grads, rel=1e-6, atol=1e-6, rtol=1e-4)
    with pytest.raises(ValueError, match="gradient_checkpointing_layers must be one of"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), gradient_checkpointing_layers="mlp")
    with pytest.raises(ValueError, match="gradient_checkpointing_mode must be one of"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), gradient_checkpointing_mode="some")


def test_checkpointing_the_first_language_layers_gives_the_same_gradients(vlm, root):
    """gradient_checkpointing_language_layers=N recomputes the vision tower and the first N decoder
    layers only; the loss and every gradient equal those of the step without checkpointing. Counts
    outside 0..depth, or with layers=vision, are refused."""
    _, loss, grads, _ = _loss_and_grads(vlm, root)
    _, ck_loss, ck_grads, flags = _loss_and_grads(
        vlm, root, gradient_checkpointing=True, gradient_checkpointing_language_layers=1
    )
    language = [flags[n] for n in sorted(flags) if "language_model.layers" in n]
    assert flags["model.visual.blocks.0"] and len(language) >= 2
    assert language == [True] + [False] * (len(language) - 1)
    _assert_same_step(loss, grads, ck_loss, ck_grads, rel=1e-6, atol=1e-6, rtol=1e-4)
    with pytest.raises(ValueError, match="with vision no language layer recomputes"):
        ActiveArenaOFTConfig(
            vlm_path=str(vlm),
            gradient_checkpointing_layers="vision",
            gradient_checkpointing_language_layers=2,
        )
    with pytest.raises(ValueError, match="a number >= 0"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), gradient_checkpointing_language_layers=-1)
    with pytest.raises(ValueError, match="decoder layers"):
        _loss_and_grads(vlm, root, gradient_checkpointing=True, gradient_checkpointing_language_layers=99)


def test_unpadded_language_model_gives_the_same_loss_and_gradients(vlm, root):
    """unpad_language_model runs the language model once per sample over its own tokens: no pad
    position is computed, and the loss and every gradient equal the padded batch's."""
    _, loss, grads, _ = _loss_and_grads(vlm, root)
    _, policy, pre, _, ds = _setup(
        vlm, root, memory="chunk", history=2, think="subtask", unpad_language_model=True
    )
    policy.train()
    calls = []
    policy.vlm.model.language_model.register_forward_pre_hook(
        lambda _m, _a, kw: calls.append(kw["inputs_embeds"].shape[:2]), with_kwargs=True
    )
    batch = collate(ds, pre, [20, len(ds) - 40])
    seq = policy.assemble(*policy.training_args(batch))
    lengths = (seq["kind"] >= 0).sum(1).tolist()
    assert len(set(lengths)) == 2  # the two samples' memories differ: the padded batch has pads
    calls.clear()
    un_loss, _ = policy.forward(batch)
    un_loss.backward()
    assert [tuple(c) for c in calls] == [(1, n) for n in lengths]
    assert float(un_loss.detach()) == pytest.approx(loss, rel=1e-5)
    for name, p in policy.named_parameters():
        if p.grad is not None:
            assert torch.allclose(p.grad, grads[name], atol=1e-6, rtol=1e-4), name


def test_residual_dtype_compute_keeps_the_streams_in_bfloat16(vlm, root):
    """residual_dtype=compute: under bfloat16 autocast the vision blocks and decoder layers receive
    bfloat16 hidden states (float32 by default); the loss stays within bfloat16 rounding of the
    float32 stream's and every gradient is finite."""
    losses, seen = {}, {}
    for residual in ("float32", "compute"):
        _, policy, pre, _, ds = _setup(
            vlm, root, memory="chunk", history=2, think="subtask", dtype="bfloat16", residual_dtype=residual
        )
        policy.train()
        dtypes = []
        for module in (policy.vlm.model.visual.blocks[-1], policy.vlm.model.language_model.layers[-1]):
            module.register_forward_pre_hook(lambda _m, args, seen=dtypes: seen.append(args[0].dtype))
        loss, _ = policy.forward(collate(ds, pre, [20, len(ds) - 40]))
        loss.backward()
        assert all(torch.isfinite(p.grad).all() for p in policy.parameters() if p.grad is not None)
        losses[residual], seen[residual] = float(loss.detach()), set(dtypes)
    assert seen == {"float32": {torch.float32}, "compute": {torch.bfloat16}}
    assert losses["compute"] == pytest.approx(losses["float32"], rel=0.05)
    with pytest.raises(ValueError, match="residual_dtype must be one of"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), residual_dtype="bfloat16")


def test_compiled_layers_give_the_same_loss_and_gradients(vlm, root):
    """compile_layers=all compiles every vision block and decoder layer in place (same modules, same
    state dict); under gradient checkpointing the loss and every gradient match the eager step's.
    Selective checkpointing cannot see inside compiled blocks: that combination is a named error."""
    torch._dynamo.reset()
    _, loss, grads, _ = _loss_and_grads(vlm, root, gradient_checkpointing=True)
    policy, c_loss, c_grads, _ = _loss_and_grads(vlm, root, gradient_checkpointing=True, compile_layers="all")
    blocks = [*policy.vlm.model.visual.blocks, *policy.vlm.model.language_model.layers]
    assert all(b._compiled_call_impl is not None for b in blocks)
    assert "model.visual.blocks.0.attn.qkv.weight" in dict(policy.vlm.named_parameters())
    _assert_same_step(loss, grads, c_loss, c_grads, rel=1e-5, atol=1e-5, rtol=1e-3)
    with pytest.raises(ValueError, match="compile_layers must be one of"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), compile_layers="mlp")
    with pytest.raises(ValueError, match="use gradient_checkpointing_mode=full"):
        ActiveArenaOFTConfig(
            vlm_path=str(vlm),
            compile_layers="all",
            gradient_checkpointing=True,
            gradient_checkpointing_mode="selective",
        )


def _backward_matmuls(vlm, root, **checkpointing) -> int:
    """Matrix multiplies run by one training step's backward pass (gradients plus any recomputation)."""
    from torch.utils._python_dispatch import TorchDispatchMode

    class CountMatmuls(TorchDispatchMode):
        n = 0

        def __torch_dispatch__(self, func, types, args=(), kwargs=None):
            CountMatmuls.n += func.overloadpacket.__name__ in ("mm", "addmm", "bmm")
            return func(*args, **(kwargs or {}))

    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="subtask", **checkpointing)
    policy.train()
    loss, _ = policy.forward(collate(ds, pre, [20, len(ds) - 40]))
    with CountMatmuls():
        loss.backward()
    return CountMatmuls.n


def test_selective_checkpointing_recomputes_no_matmul(vlm, root):
    """Selective checkpointing keeps the matrix multiplies' outputs: its backward pass runs as many
    as the step without checkpointing, full checkpointing's runs the forward's again."""
    plain = _backward_matmuls(vlm, root)
    full = _backward_matmuls(vlm, root, gradient_checkpointing=True)
    selective = _backward_matmuls(
        vlm, root, gradient_checkpointing=True, gradient_checkpointing_mode="selective"
    )
    assert selective == plain < full


def test_precision_defaults_follow_the_device():
    feats = {"observation.images.head": PolicyFeature(FeatureType.VISUAL, (3, 384, 512))}
    cpu = ActiveArenaOFTConfig(device="cpu", input_features=feats)
    assert cpu.dtype == "auto" and cpu.weights_dtype == "float32" and not cpu.autocast_bfloat16
    cuda = ActiveArenaOFTConfig(device="cpu", input_features=feats)
    cuda.device = "cuda"
    assert cuda.autocast_bfloat16
    with pytest.raises(ValueError, match="weights_dtype must be one of"):
        ActiveArenaOFTConfig(device="cpu", weights_dtype="float16")


def test_two_process_ddp_keeps_the_replicas_identical(vlm, root, tmp_path):
    """Data parallel training as lerobot-train runs it under a distributed launcher (DDP over gloo on
    the CPU, two fresh processes from torchrun): each process sees different samples, the
    all-reduced gradients keep both replicas equal."""
    out = tmp_path / "ddp.pt"
    run = _torchrun(
        [
            "--master_port=29532",
            Path(__file__).parents[1] / "helpers" / "ddp_two_steps.py",
            vlm,
            root,
            REPO,
            out,
        ],
        timeout=600,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    res = torch.load(out)
    after, losses = res["after"], res["losses"]
    assert after.shape[0] == 2 and torch.equal(after[0], after[1])  # bit-identical replicas
    assert not torch.equal(after[0], res["before"])  # and they trained
    assert not torch.equal(losses[0], losses[1])  # on different data


@pytest.mark.slow
def test_lerobot_train_runs_a_preset_on_two_processes(vlm, root, tmp_path):
    out = tmp_path / "train"
    run = _torchrun(
        [
            "--master_port=29531",
            _exe("lerobot-train"),
            f"--config_path={CONFIGS / 'oft_subtask_action_6_ws.json'}",
            f"--dataset.repo_id={REPO}",
            f"--dataset.root={root}",
            f"--policy.vlm_path={vlm}",
            "--policy.device=cpu",
            "--policy.state_hidden=32",
            "--steps=2",
            "--batch_size=2",
            "--num_workers=0",
            "--save_freq=2",
            "--log_freq=1",
            f"--output_dir={out}",
        ],
        timeout=900,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    assert "Effective batch size: 2 x 2 = 4" in run.stdout + run.stderr  # two processes, one replica each
    assert (out / "checkpoints" / "last" / "pretrained_model" / "model.safetensors").exists()


def test_padded_history_frames_are_never_processed(vlm, root):
    """A frame before the episode start costs nothing: it skips the image processor (zeros in the
    batch) and the policy drops it from the sequence."""
    cfg, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=4, think="none")
    step = next(s for s in pre.steps if type(s).__name__ == "ActiveArenaVLMInputsStep")
    seen = []
    real = step.processor.image_processor

    class Counting:
        def __call__(self, images, **kw):
            seen.append(len(images))
            return real(images=images, **kw)

    step.processor.image_processor = Counting()
    try:
        batch = collate(ds, pre, [20, len(ds) - 40])  # frame 20: 1 history frame present; later: all 4
    finally:
        step.processor.image_processor = real
    valid = batch["observation.vlm.frame_valid"]
    assert valid.sum(1).tolist() == [2, 5] and seen == [7]
    # the pixels hold the 7 present frames only, in (sample, frame) order
    assert len(batch[PIXELS]) == 7 and (batch[PIXELS].abs().sum((-1, -2)) > 0).all()
    loss, _ = policy.forward(batch)
    assert torch.isfinite(loss)


def test_images_are_processed_on_the_policy_device(vlm, root):
    """The image processor runs where the policy runs (on a GPU: off the training loop's CPU); a
    checkpoint saved on CUDA still evaluates on a machine without it."""
    cfg, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="none")
    step = next(s for s in pre.steps if type(s).__name__ == "ActiveArenaVLMInputsStep")
    assert step.device == cfg.device and step.get_config()["device"] == cfg.device
    calls = []
    real = step.processor.image_processor

    class Recording:
        def __call__(self, images, **kw):
            calls.append((kw.get("device"), {im.device for im in images}))
            return real(images=images, **kw)

    step.processor.image_processor = Recording()
    try:
        step.device = "cuda"
        collate(ds, pre, [20])
    finally:
        step.processor.image_processor = real
    expected = torch.device("cuda") if torch.cuda.is_available() else torch.device("cpu")
    assert calls == [(expected, {expected})]


def test_a_frozen_memory_tower_reads_the_memory_bank_as_loaded(vlm, root):
    """memory_vision=frozen: once the policy's own tower has moved away from the one loaded, the
    memory bank's features are still the frozen copy's (what a vision cache made from the loaded
    tower holds), the current frame goes through the trained tower, and the chunk is the one of
    encoding the same frames afresh that way."""
    _, policy, pre, _, _ = _setup(vlm, root, memory="chunk", history=2, think="none", memory_vision="frozen")
    with torch.no_grad():
        for p in policy.vlm.model.visual.parameters():
            p.add_(0.05 * torch.randn_like(p))  # the trained tower, no longer the loaded one
    policy.eval()
    for t, obs, _ in _scripted_observations(33):
        batch = pre(obs)
        if t == 32:
            pixels, grid, valid, state, _ = policy.history_batch(batch)
            with torch.no_grad():
                fresh, _ = policy.encode(
                    pixels,
                    grid,
                    valid,
                    state,
                    batch["observation.vlm.prefix_ids"],
                    batch["observation.vlm.prompt_ids"],
                    batch["observation.vlm.prompt_mask"],
                )
        action = policy.select_action(batch)
    assert torch.allclose(action, fresh[:, 0], atol=1e-5)
    bank = policy.memory(0)
    assert [e["t"] for e in bank] == [16, 32]
    # frame 32 is encoded by the copy at its first use as memory; frame 16 was at step 32
    assert bank[1]["vision"] is None
    for entry in bank[:1]:
        with torch.no_grad():
            frozen = policy.vision_features(entry["pixels"], entry["grid"][None], memory=True)[0][0]
            trained = policy.vision_features(entry["pixels"], entry["grid"][None])[0][0]
        assert torch.allclose(entry["vision"][0], frozen, atol=1e-6)
        assert not torch.allclose(entry["vision"][0], trained, atol=1e-3)


def _assert_the_ablation_changes_only_the_sample_with_memory(policy, batch, ablation):
    """Of a dataset batch's two samples (one with memory frames, one at its episode's first frame),
    ``memory_ablation`` changes the first one's chunk and not the second one's."""
    with torch.no_grad():
        real = policy.predict_action_chunk(dict(batch))
        policy.config.memory_ablation = ablation
        ablated = policy.predict_action_chunk(dict(batch))
    assert not torch.allclose(real[0], ablated[0], atol=1e-4)
    assert torch.allclose(real[1], ablated[1], atol=1e-5)


def _chunk_memory_policy_at_step_32(vlm, root):
    """A chunk-memory policy (K = 2) played on scripted observations to step 32 (memory frames 0 and
    16), the step's preprocessed batch and its prompt arguments for ``encode``."""
    _, policy, pre, _, _ = _setup(vlm, root, memory="chunk", history=2, think="none")
    policy.eval()
    for t, obs, _ in _scripted_observations(33):
        batch = pre(obs)
        if t == 32:
            break
        policy.select_action(batch)
    args = (
        batch["observation.vlm.prefix_ids"],
        batch["observation.vlm.prompt_ids"],
        batch["observation.vlm.prompt_mask"],
    )
    return policy, batch, args


def test_blanked_memory_keeps_its_slots_and_states_but_not_what_it_saw(vlm, root):
    """memory_ablation=blank (evaluation): the memory frames reach the backbone as gray images in the
    same slots with the same state tokens; the bank keeps the real frames; the chunk changes."""
    policy, batch, args = _chunk_memory_policy_at_step_32(vlm, root)
    real = policy.history_batch(batch)
    policy.config.memory_ablation = "blank"
    blank = policy.history_batch(batch)
    assert [e["t"] for e in policy.memory(0)] == [0, 16]
    assert torch.equal(real[2], blank[2]) and torch.equal(real[3], blank[3])  # valid slots, states
    # one env, all three slots present: the packed pixels are its two memory frames, then the current
    assert len(real[0]) == len(blank[0]) == 3
    assert torch.count_nonzero(real[0][:2]) > 0 and torch.count_nonzero(blank[0][:2]) == 0
    assert torch.equal(real[0][2], blank[0][2])  # the current frame is untouched
    assert all(torch.count_nonzero(e["pixels"]) > 0 for e in policy.memory(0))
    with torch.no_grad():
        a_real = policy.encode(*real[:4], *args)[0]
        a_blank = policy.encode(*blank[:4], *args)[0]
    assert not torch.allclose(a_real, a_blank)


def test_dropped_memory_leaves_only_the_current_frame_as_at_an_episode_start(vlm, root):
    """memory_ablation=drop (evaluation): the decision reads no memory slot, as at an episode's first
    step; the bank keeps its frames; the chunk changes."""
    policy, batch, args = _chunk_memory_policy_at_step_32(vlm, root)
    real = policy.history_batch(batch)
    policy.config.memory_ablation = "drop"
    dropped = policy.history_batch(batch)
    assert real[2].tolist() == [[True, True, True]]
    assert dropped[2].tolist() == [[False, False, True]]
    assert len(dropped[0]) == 1 and torch.equal(dropped[0][0], real[0][2])
    assert [e["t"] for e in policy.memory(0)] == [0, 16]
    with torch.no_grad():
        a_real = policy.encode(*real[:4], *args)[0]
        a_dropped = policy.encode(*dropped[:4], *args)[0]
    assert not torch.allclose(a_real, a_dropped)


def test_dropped_memory_in_a_dataset_batch_keeps_only_the_current_frames(vlm, root):
    """memory_ablation=drop on a dataset batch: only the current frames' pixel rows remain and every
    memory slot is absent; a sample with memory frames gets another chunk, one at its episode's first
    frame the same."""
    from lerobot_activearena.policies.activearena_vla.helpers import drop_memory_frames

    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="none")
    policy.eval()
    batch = collate(ds, pre, [70, 0])
    pixels, valid = batch[PIXELS], batch["observation.vlm.frame_valid"]
    grid = batch["observation.vlm.image_grid_thw"]
    kept, kept_valid = drop_memory_frames(pixels, valid, grid)
    assert kept_valid.tolist() == [[False, False, True], [False, False, True]]
    assert torch.equal(kept, pixels[2:])
    _assert_the_ablation_changes_only_the_sample_with_memory(policy, batch, "drop")
    with pytest.raises(ValueError, match="vision cache"):
        drop_memory_frames(pixels[2:], valid, grid)


def test_memory_dropout_trains_a_sample_as_if_its_memory_were_not_there(vlm, root):
    """memory_dropout (training): a dropped sample is trained as at its episode's first frame, on its
    current frame alone: at 1.0 the loss is the one of the batch with its memory slots made absent by
    hand; at 0 or in evaluation mode the memory is read."""
    from lerobot_activearena.policies.activearena_vla.helpers import drop_memory_frames

    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="subtask")
    batch = collate(ds, pre, [70, 0])
    valid = batch["observation.vlm.frame_valid"]
    by_hand = dict(batch)
    by_hand[PIXELS], by_hand["observation.vlm.frame_valid"] = drop_memory_frames(
        batch[PIXELS], valid, batch["observation.vlm.image_grid_thw"]
    )
    policy.train()
    with torch.no_grad():
        full = policy.forward(dict(batch))[0]
        absent = policy.forward(by_hand)[0]
        policy.config.memory_dropout = 1.0
        dropped = policy.forward(dict(batch))[0]
    assert not torch.allclose(full, absent)
    assert torch.allclose(dropped, absent, atol=1e-6)
    with pytest.raises(
        ValueError, match="memory_dropout leaves a sample's memory frames out: it needs a memory"
    ):
        ActiveArenaOFTConfig(memory="none", memory_dropout=0.5, device="cpu")
    with pytest.raises(ValueError, match="memory_dropout is a probability"):
        ActiveArenaOFTConfig(memory="chunk", memory_dropout=1.5, device="cpu")


def test_memory_readers_span_lets_only_the_think_span_read_the_memory(vlm, root):
    """memory_readers=span: graying the memory images changes the last-layer states of the think span
    (and of the memory itself); the prompt and the current frame never attend to a memory frame, nor do
    the action queries, which see it only through the span: without a span their states stay as they
    were. With all, the queries change too. Cached decoding decodes what uncached decoding does."""
    from lerobot_activearena.policies.activearena_vla.helpers import blank_memory_pixels

    _, policy, pre, _, ds = _setup(
        vlm, root, memory="chunk", history=2, think="subtask", think_first=True, memory_readers="span"
    )
    batch = collate(ds, pre, [70, len(ds) - 10])
    gray = dict(batch)
    gray[PIXELS] = blank_memory_pixels(
        batch[PIXELS], batch["observation.vlm.frame_valid"], batch["observation.vlm.image_grid_thw"]
    )
    policy.eval()

    def change(span: bool):
        args, gray_args = (list(policy.training_args(dict(b))) for b in (batch, gray))
        if not span:
            args[-2:] = gray_args[-2:] = None, None
        with torch.no_grad():
            h, kind, _ = policy.hidden_states(*args)
            h_gray = policy.hidden_states(*gray_args)[0]
        memory = policy.assemble(*args)["memory"]
        return (h - h_gray).abs().amax(-1), kind, memory

    diff, kind, memory = change(span=True)
    assert memory.sum(1).min() > 0  # both samples remember something
    later = (memory.long().cumsum(1) > 0) & ~memory  # after the first memory frame
    before_span = later & (kind >= 0) & ((kind == THINK).long().cumsum(1) == 0)
    assert diff[before_span].max() < 1e-5  # the current frame, its state and the prompt
    assert diff[kind == THINK].min() > 1e-4 and diff[memory].max() > 1e-4
    diff, kind, _ = change(span=False)
    assert (kind == QUERY).any() and diff[kind == QUERY].max() < 1e-5
    policy.config.memory_readers = "all"
    diff, kind, _ = change(span=False)
    assert diff[kind == QUERY].min() > 1e-4
    policy.config.memory_readers = "span"
    target = batch[THINK_IDS][0][batch[THINK_MASK][0]].tolist()
    one = collate(ds, pre, [len(ds) - 10])
    with torch.no_grad():
        cached = policy.greedy_decode(_encode_args(one), target[:1], target[-2], 6, use_cache=True)
        full = policy.greedy_decode(_encode_args(one), target[:1], target[-2], 6, use_cache=False)
    assert cached[0] == full[0]
    for a, b in zip(cached[1], full[1], strict=True):
        assert torch.allclose(a, b, atol=1e-4), (a - b).abs().max()
    with pytest.raises(ValueError, match="memory_readers=span lets only the think span"):
        ActiveArenaOFTConfig(memory="chunk", history=2, think="none", memory_readers="span", device="cpu")
    with pytest.raises(ValueError, match="add --policy.think_first=true"):
        ActiveArenaOFTConfig(memory="chunk", history=2, think="subtask", memory_readers="span", device="cpu")
    with pytest.raises(ValueError, match="flash-attn"):
        ActiveArenaOFTConfig(
            memory="chunk",
            history=2,
            think="subtask",
            think_first=True,
            memory_readers="span",
            attn_implementation="flash_attention_2",
            device="cpu",
        )


def test_a_memory_checkpoint_warm_started_from_a_memory_free_one_acts_as_it_does(vlm, root, tmp_path):
    """analysis/policies/warm_start_memory.py: the memory-free checkpoint's weights in a chunk-memory
    checkpoint's layout. Loaded with memory_readers=span, at an episode's first frame (nothing in
    memory) its chunk is the memory-free policy's, not the layout checkpoint's; its memory tower is the
    layout's. A checkpoint with a memory is refused as the memory-free one."""
    from helpers.analysis_scripts import load

    warm = load("analysis/policies/warm_start_memory.py")
    common = {"think": "subtask", "think_first": True}
    saved, batches, chunks = {}, {}, {}
    for name, extra in (
        ("free", {"memory": "none", "history": 0}),
        ("memory", {"memory": "chunk", "history": 2, "memory_vision": "frozen"}),
    ):
        cfg, policy, pre, _, ds = _setup(vlm, root, **common, **extra)
        with torch.no_grad():  # tell the two apart: the memory preset's weights are not the memory-free ones
            for param in policy.parameters():
                param.add_(0.01 * torch.randn_like(param) if name == "memory" else 0)
        saved[name] = tmp_path / name
        policy.save_pretrained(saved[name])
        pre.save_pretrained(saved[name])
        batches[name] = collate(ds, pre, [0])
        assert not batches[name]["observation.vlm.frame_valid"][0, :-1].any()  # the first frame
        policy.eval()
        with torch.no_grad():
            b = batches[name]
            chunks[name] = policy.encode(*_encode_args(b), b[THINK_IDS], b[THINK_MASK])[0]
        if name == "memory":
            memory_cfg, tower = cfg, {k: v.clone() for k, v in policy.memory_tower.state_dict().items()}
    counts = warm.warm_start(saved["free"], saved["memory"], tmp_path / "warm")
    assert counts["layout"] == len(tower)
    merged = ActiveArenaOFTPolicy.from_pretrained(
        tmp_path / "warm", config=dataclasses.replace(memory_cfg, memory_readers="span")
    )
    merged.eval()
    b = batches["memory"]
    with torch.no_grad():
        chunk = merged.encode(*_encode_args(b), b[THINK_IDS], b[THINK_MASK])[0]
    assert torch.allclose(chunk, chunks["free"], atol=1e-5)
    assert (chunk - chunks["memory"]).abs().max() > 1e-3
    assert all(torch.equal(v, tower[k]) for k, v in merged.memory_tower.state_dict().items())
    with pytest.raises(SystemExit, match="has a memory"):
        warm.warm_start(saved["memory"], saved["memory"], tmp_path / "again")


def test_memory_dropout_takes_out_cached_frames_and_carried_pixels_alike():
    """drop_sample_memory on a batch whose memory frames come partly from a vision cache (no pixels)
    and partly as pixel rows: a dropped sample loses its memory slots, cache entries and pixel rows;
    the other sample and every current frame keep theirs."""
    from lerobot_activearena.policies.activearena_vla.helpers import drop_sample_memory

    grid = torch.tensor([1, 2, 2]).repeat(2, 3, 1)  # 2 samples x 3 slots, 4 patches a frame
    valid = torch.tensor([[True, True, True], [False, True, True]])
    cache = {(0, 0): {"vision": "a"}, (1, 1): {"vision": "b"}}  # from the table: no pixel rows
    # carried in (sample, slot) order: (0, 1), (0, 2), (1, 2)
    pixels = torch.stack([torch.full((4, 3), float(v)) for v in (1, 2, 3)])
    kept, kept_valid, kept_cache = drop_sample_memory(pixels, grid, valid, cache, torch.tensor([True, False]))
    assert kept_valid.tolist() == [[False, False, True], [False, True, True]]
    assert [float(r[0, 0]) for r in kept] == [2.0, 3.0]
    assert kept_cache == {(1, 1): {"vision": "b"}}
    same = drop_sample_memory(pixels, grid, valid, cache, torch.tensor([False, False]))
    assert same[0] is pixels and same[1] is valid and same[2] is cache


def test_blanked_memory_in_a_dataset_batch_grays_only_the_memory_frames(vlm, root):
    """memory_ablation=blank on a dataset batch (open-loop scoring): the present memory frames' pixel
    rows turn gray and the current frames' stay; the chunk of a sample with memory frames changes,
    that of a sample at its episode's first frame (no memory yet) does not."""
    from lerobot_activearena.policies.activearena_vla.helpers import blank_memory_pixels

    _, policy, pre, _, ds = _setup(vlm, root, memory="chunk", history=2, think="none")
    policy.eval()
    batch = collate(ds, pre, [70, 0])
    pixels, valid = batch[PIXELS], batch["observation.vlm.frame_valid"]
    assert valid.sum(1).tolist() == [3, 1] and len(pixels) == 4
    grid = batch["observation.vlm.image_grid_thw"]
    blank = blank_memory_pixels(pixels, valid, grid)
    # packed in (sample, slot) order: sample 0's two memory frames and its current one, sample 1's current
    assert torch.count_nonzero(pixels[:2]) > 0 and torch.count_nonzero(blank[:2]) == 0
    assert torch.equal(blank[2:], pixels[2:])
    _assert_the_ablation_changes_only_the_sample_with_memory(policy, batch, "blank")
    with pytest.raises(ValueError, match="vision cache"):
        blank_memory_pixels(pixels[2:], valid, grid)


def test_small_presets_differ_only_in_their_memory():
    """configs/policy/small: the CPU-sized pair of the paper's memory comparison."""
    small = CONFIGS / "small"
    chunk = json.loads((small / "oft_subtask_action_12_ws.json").read_text())
    free = json.loads((small / "oft_subtask_no_0_ws.json").read_text())
    for cfg in (chunk, free):
        cfg.pop("job_name")
    diff = {k for k in chunk["policy"] if chunk["policy"][k] != free["policy"].get(k)}
    assert diff == {"memory", "history"} and {k for k in chunk if chunk[k] != free[k]} == {"policy"}
    fields = {k: v for k, v in chunk["policy"].items() if k not in ("type", "vlm_path")}
    cfg = ActiveArenaOFTConfig(**fields)
    assert cfg.observation_delta_indices == [-16 * k for k in range(12, 0, -1)] + [0]
    assert cfg.image_max_pixels == 96 * 128 and not cfg.gradient_checkpointing
    assert chunk["policy"]["scheduler_decay_steps"] == chunk["steps"]


def test_the_span_read_inspection_presets_change_only_who_reads_the_memory():
    """oft_decision_action_12_ws_inspection_span: the one-run chunk-12 preset with memory_readers=span,
    nothing else changed; _span_from_no_0 also continues the memory-free checkpoint's warm-started copy
    on a shorter, lower schedule."""
    small = CONFIGS / "small"
    base = json.loads((small / "oft_decision_action_12_ws_inspection.json").read_text())
    span = json.loads((small / "oft_decision_action_12_ws_inspection_span.json").read_text())
    warm = json.loads((small / "oft_decision_action_12_ws_inspection_span_from_no_0.json").read_text())

    def changed(a, b):
        return {
            k for k in a["policy"].keys() | b["policy"].keys() if a["policy"].get(k) != b["policy"].get(k)
        }

    assert changed(span, base) == {"memory_readers"} and span["policy"]["memory_readers"] == "span"
    assert {k for k in span if span[k] != base[k]} == {"policy", "job_name"}
    assert changed(warm, span) == {
        "pretrained_path",
        "optimizer_lr",
        "head_lr",
        "vision_lr",
        "scheduler_decay_steps",
    }
    assert warm["policy"]["pretrained_path"] == "outputs/warm/no_0_as_action_12"
    assert warm["steps"] == warm["policy"]["scheduler_decay_steps"] < base["steps"]
    assert {k for k in warm if warm[k] != span[k]} == {"policy", "steps", "job_name"}


@pytest.mark.parametrize("preset", ["oft_subtask_action_12_ws", "oft_subtask_action_12_ws_grounded_bell"])
def test_small_jitter_presets_add_only_act_cpu_jitter_colour_jitter(preset):
    """<preset>_jitter: the chunk-12 preset with the image transforms of ACT's colour-jitter preset,
    nothing else changed."""
    base = json.loads((CONFIGS / "small" / f"{preset}.json").read_text())
    jitter = json.loads((CONFIGS / "small" / f"{preset}_jitter.json").read_text())
    act = json.loads((CONFIGS / "baselines" / "act_cpu_jitter.json").read_text())
    assert jitter["dataset"] == dict(base["dataset"], image_transforms=act["dataset"]["image_transforms"])
    assert {"brightness", "hue"} <= set(jitter["dataset"]["image_transforms"]["tfs"])
    assert {k for k in jitter if jitter[k] != base[k]} == {"dataset", "job_name"}


def test_small_presets_at_192_x_256_differ_only_in_the_image(tmp_path):
    """The _p32 pair reads 192 x 256 frames (where the buttons' digits are legible) with a 32 px patch
    backbone: the same 12 tokens per image as the 96 x 128 pair, nothing else changed."""
    small = CONFIGS / "small"
    for name in ("oft_subtask_action_12_ws", "oft_subtask_no_0_ws"):
        base = json.loads((small / f"{name}.json").read_text())
        wide = json.loads((small / f"{name}_p32.json").read_text())
        changed = {k for k in wide["policy"] if wide["policy"][k] != base["policy"][k]}
        assert changed == {"vlm_path", "image_max_pixels"} and wide["policy"]["image_max_pixels"] == 192 * 256
        assert wide["dataset"] == dict(base["dataset"], repo_id=base["dataset"]["repo_id"] + "_192")
        assert {k for k in wide if wide[k] != base[k]} == {"policy", "dataset", "job_name"}


def test_small_presets_with_the_wider_vision_tower_differ_only_in_the_backbone():
    """The _v256d4 pair: the 96 x 128 pair on a backbone whose vision tower is 4 blocks of width 256
    (``activearena-make-tiny-vlm --vision-hidden 256 --vision-depth 4``), nothing else changed."""
    small = CONFIGS / "small"
    for name in ("oft_subtask_action_12_ws", "oft_subtask_no_0_ws"):
        base = json.loads((small / f"{name}.json").read_text())
        wide = json.loads((small / f"{name}_v256d4.json").read_text())
        changed = {k for k in wide["policy"] if wide["policy"][k] != base["policy"][k]}
        assert changed == {"vlm_path"} and wide["policy"]["vlm_path"] == "outputs/small_vlm_v256d4"
        assert {k for k in wide if wide[k] != base[k]} == {"policy", "job_name"}


def test_grounded_bell_presets_are_the_wider_pair_with_the_grounded_backbone_and_the_bell_recipe():
    """The _grounded_bell pair: the _v256d4 pair on the backbone grounded by activearena-ground-vision,
    with the bell recipe's build, batch and schedule; the two still differ only in the memory."""
    small = CONFIGS / "small"
    pair = {}
    for name in ("oft_subtask_action_12_ws", "oft_subtask_no_0_ws"):
        wide = json.loads((small / f"{name}_v256d4.json").read_text())
        grounded = pair[name] = json.loads((small / f"{name}_grounded_bell.json").read_text())
        changed = {k for k in grounded["policy"] if grounded["policy"][k] != wide["policy"][k]}
        assert changed == {"vlm_path", "scheduler_decay_steps"}
        assert grounded["policy"]["vlm_path"] == "outputs/small_vlm_v256d4_grounded_bell"
        assert grounded["dataset"] == dict(wide["dataset"], repo_id="local/cpu_click_bell_200_p16")
        assert (grounded["batch_size"], grounded["steps"], grounded["save_freq"]) == (64, 3000, 250)
        assert grounded["policy"]["scheduler_decay_steps"] == grounded["steps"]
        assert {k for k in grounded if grounded[k] != wide[k]} == {
            "policy",
            "dataset",
            "batch_size",
            "steps",
            "save_freq",
            "job_name",
        }
    chunk, free = pair.values()
    assert {k for k in chunk["policy"] if chunk["policy"][k] != free["policy"][k]} == {"memory", "history"}
    from lerobot.configs.train import TrainPipelineConfig

    cfg = TrainPipelineConfig.from_pretrained(small / "oft_subtask_action_12_ws_grounded_bell.json")
    assert (cfg.policy.type, cfg.batch_size, cfg.policy.history) == ("activearena_oft", 64, 12)


def test_grounded_count_presets_are_the_bell_pair_at_192_x_256_on_the_count_build():
    """The _grounded_count pair: the _grounded_bell recipe on the counting task's 192 x 256 build (where
    the buttons' digits are legible), read by the 32 px patch backbone grounded on that build."""
    small = CONFIGS / "small"
    pair = {}
    for name in ("oft_subtask_action_12_ws", "oft_subtask_no_0_ws"):
        bell = json.loads((small / f"{name}_grounded_bell.json").read_text())
        count = pair[name] = json.loads((small / f"{name}_grounded_count.json").read_text())
        changed = {k for k in count["policy"] if count["policy"][k] != bell["policy"][k]}
        assert changed == {"vlm_path", "image_max_pixels"}
        assert count["policy"]["vlm_path"] == "outputs/small_vlm_v256d4_p32_grounded_count"
        assert count["policy"]["image_max_pixels"] == 192 * 256
        assert count["dataset"] == dict(bell["dataset"], repo_id="local/cpu_count_200_p16_192")
        assert {k for k in count if count[k] != bell[k]} == {"policy", "dataset", "job_name"}
    chunk, free = pair.values()
    assert {k for k in chunk["policy"] if chunk["policy"][k] != free["policy"][k]} == {"memory", "history"}
    from lerobot.configs.train import TrainPipelineConfig

    cfg = TrainPipelineConfig.from_pretrained(small / "oft_subtask_no_0_ws_grounded_count.json")
    assert (cfg.policy.memory, cfg.policy.image_max_pixels, cfg.steps) == ("none", 49152, 3000)


def test_small_stateless_preset_differs_from_the_chunk_12_preset_as_the_papers_pair():
    """oft_subtask_action_12_wos: the small chunk-12 preset without state tokens, the change between the
    paper's oft_subtask_action_12_ws and _wos presets."""
    small, full = {}, {}
    for suffix in ("ws", "wos"):
        small[suffix] = json.loads((CONFIGS / "small" / f"oft_subtask_action_12_{suffix}.json").read_text())
        full[suffix] = json.loads((CONFIGS / f"oft_subtask_action_12_{suffix}.json").read_text())
    for pair in (small, full):
        changed = {k for k in pair["ws"]["policy"] if pair["ws"]["policy"][k] != pair["wos"]["policy"].get(k)}
        assert changed == {"use_state"} and not pair["wos"]["policy"]["use_state"]
        assert {k for k in pair["ws"] if pair["ws"][k] != pair["wos"][k]} == {"policy", "job_name"}


def test_a_32_px_patch_backbone_reads_twice_the_resolution_as_the_same_tokens(tmp_path, root):
    """make_tiny_vlm(patch=32) at image_max_pixels 192 * 256: a 192 x 256 frame becomes the 6 x 8
    patch grid (12 merged tokens) that 16 px patches make of 96 x 128, every pixel in the patch
    embedding; the policy trains on it; a budget below one token is named."""
    from lerobot.processor import TransitionKey

    from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import (
        GRID,
        ActiveArenaVLMInputsStep,
    )
    from lerobot_activearena.tasks.registry import task_texts

    p16 = make_tiny_vlm(tmp_path / "p16", texts=task_texts())
    p32 = make_tiny_vlm(tmp_path / "p32", texts=task_texts(), patch=32)
    grids = {}
    for vlm, patch, (h, w) in ((p16, 16, (96, 128)), (p32, 32, (192, 256))):
        step = ActiveArenaVLMInputsStep(vlm_path=str(vlm), image_max_pixels=h * w, defer_env_frames=False)
        out = step(
            {
                TransitionKey.OBSERVATION: {"observation.images.head": torch.rand(1, 3, h, w)},
                TransitionKey.COMPLEMENTARY_DATA: {"task": "press the button"},
            }
        )
        grids[h] = out[TransitionKey.OBSERVATION][GRID]
        assert out[TransitionKey.OBSERVATION][PIXELS].shape[-2:] == (48, 3 * 2 * patch**2)  # 2 frames a patch
    assert grids[96].tolist() == grids[192].tolist() == [[[1, 6, 8]]]
    cfg, policy, pre, _, ds = _setup(p32, root, memory="chunk", history=2, think="subtask")
    loss, _ = policy.forward(collate(ds, pre, [20, len(ds) - 10]))
    loss.backward()
    embed = policy.vlm.model.visual.patch_embed
    assert torch.isfinite(loss) and embed.proj.weight.grad.abs().sum() > 0
    assert type(embed).__name__ == "LinearPatchEmbed"
    with pytest.raises(ValueError, match="image_max_pixels=1024 is below one token"):
        ActiveArenaVLMInputsStep(vlm_path=str(p32), image_max_pixels=1024)


def test_a_wider_deeper_vision_tower_feeds_the_same_language_width(tmp_path, root):
    """make_tiny_vlm(vision_hidden=, vision_depth=): the tower's blocks and width change, its merger
    still projects to the language width, and the policy trains on it; the defaults are the tower of
    width ``hidden`` and 2 blocks; a bad size or the 2B architecture is named."""
    from transformers import AutoConfig

    base = AutoConfig.from_pretrained(make_tiny_vlm(tmp_path / "base", hidden=64))
    assert (base.vision_config.depth, base.vision_config.hidden_size) == (2, 64)
    path = make_tiny_vlm(tmp_path / "wide", hidden=64, vision_hidden=96, vision_depth=3)
    vision = AutoConfig.from_pretrained(path).vision_config
    assert (vision.depth, vision.hidden_size, vision.out_hidden_size) == (3, 96, 64)
    cfg, policy, pre, _, ds = _setup(path, root, memory="chunk", history=2, think="subtask")
    visual = policy.vlm.model.visual
    assert len(visual.blocks) == 3 and visual.blocks[0].mlp.linear_fc1.in_features == 96
    loss, _ = policy.forward(collate(ds, pre, [20, len(ds) - 10]))
    loss.backward()
    assert torch.isfinite(loss) and visual.blocks[2].mlp.linear_fc2.weight.grad.abs().sum() > 0
    with pytest.raises(ValueError, match="depth >= 2 and a width that is a multiple of 4"):
        make_tiny_vlm(tmp_path / "bad", vision_hidden=90)
    with pytest.raises(ValueError, match="tiny architecture only"):
        make_tiny_vlm(tmp_path / "big", architecture="qwen3-vl-2b", vision_depth=4)


@pytest.mark.parametrize("patch", [16, 32])
def test_the_linear_patch_embedding_equals_qwens_convolution(tmp_path, patch):
    """patch_embed_as_linear: the same embeddings and weight gradients as Qwen3-VL's Conv3d, the same
    state dict (checkpoints unchanged); the policy loads its backbone that way."""
    from transformers import Qwen3VLForConditionalGeneration

    from lerobot_activearena.policies.activearena_vla.patch_embedding import (
        LinearPatchEmbed,
        patch_embed_as_linear,
    )

    path = make_tiny_vlm(tmp_path / "vlm", patch=patch)
    conv = Qwen3VLForConditionalGeneration.from_pretrained(path)
    linear = Qwen3VLForConditionalGeneration.from_pretrained(path)
    patch_embed_as_linear(linear)
    assert type(linear.model.visual.patch_embed) is LinearPatchEmbed
    assert linear.state_dict().keys() == conv.state_dict().keys()
    x = torch.randn(40, 3 * 2 * patch * patch)
    outs = []
    for model in (conv, linear):
        y = model.model.visual.patch_embed(x)
        (y**2).sum().backward()
        outs.append((y, model.model.visual.patch_embed.proj.weight.grad))
    assert outs[0][0].shape == (40, 64)
    assert torch.allclose(outs[0][0], outs[1][0], atol=1e-5)
    grad_conv, grad_linear = outs[0][1], outs[1][1]
    assert (grad_conv - grad_linear).abs().max() < 1e-5 * grad_conv.abs().max() * x.shape[0]
    other = SimpleNamespace(model=SimpleNamespace(visual=SimpleNamespace(patch_embed=torch.nn.Linear(2, 2))))
    with pytest.raises(TypeError, match="expected Qwen3-VL's patch embedding, got Linear"):
        patch_embed_as_linear(other)


@pytest.mark.parametrize("sizes", [[(1, 4, 6)] * 3, [(1, 4, 6), (1, 2, 4), (1, 4, 6)]])
def test_batched_vision_attention_equals_qwens_per_image_loop(tmp_path, sizes, monkeypatch):
    """batch_vision_attention: images of one size attend in one call, mixed sizes take Qwen's loop;
    the vision tower's features and weight gradients are Qwen3-VL's own, with the same state dict."""
    from transformers import Qwen3VLForConditionalGeneration

    from lerobot_activearena.policies.activearena_vla import vision_attention
    from lerobot_activearena.policies.activearena_vla.vision_attention import (
        BatchedVisionAttention,
        batch_vision_attention,
    )

    calls = []

    def counting(*args, **kwargs):
        calls.append(args[0].shape[0])
        return torch.nn.functional.scaled_dot_product_attention(*args, **kwargs)

    monkeypatch.setattr(
        vision_attention, "functional", SimpleNamespace(scaled_dot_product_attention=counting)
    )

    path = make_tiny_vlm(tmp_path / "vlm")
    loop = Qwen3VLForConditionalGeneration.from_pretrained(path)
    batched = Qwen3VLForConditionalGeneration.from_pretrained(path)
    batch_vision_attention(batched)
    assert all(type(b.attn) is BatchedVisionAttention for b in batched.model.visual.blocks)
    assert batched.state_dict().keys() == loop.state_dict().keys()
    grid = torch.tensor(sizes)
    patch = batched.config.vision_config.patch_size
    pixels = torch.randn(
        int(grid.prod(-1).sum()), 3 * 2 * patch * patch, generator=torch.Generator().manual_seed(0)
    )
    outs = []
    for model in (loop, batched):
        features = model.model.get_image_features(pixels, grid).pooler_output
        merged = torch.cat(list(features))
        (merged**2).sum().backward()
        outs.append((merged, model.model.visual.blocks[0].attn.qkv.weight.grad))
    assert torch.allclose(outs[0][0], outs[1][0], atol=1e-5)
    assert torch.allclose(outs[0][1], outs[1][1], atol=1e-5, rtol=1e-4)
    blocks = len(batched.model.visual.blocks)
    assert calls == (
        [3] * blocks if len(set(sizes)) == 1 else []
    )  # one call of 3 images per block, or the loop
    other = SimpleNamespace(
        model=SimpleNamespace(visual=SimpleNamespace(blocks=[SimpleNamespace(attn=torch.nn.Linear(2, 2))]))
    )
    with pytest.raises(TypeError, match="expected Qwen3-VL's vision attention, got Linear"):
        batch_vision_attention(other)


def _with_red_pad_reading(root, tmp_path, episode: int = 0, **sidecar):
    """A copy of the dataset whose ``episode`` read a hidden face at frame 20 and decided "place on the
    red pad" (its sidecar's ``expert_notes``; ``sidecar`` sets further keys)."""
    copy = tmp_path / "data"
    shutil.copytree(root, copy)
    side_path = copy / f"meta/activearena/sidecars/episode_{episode:06d}.json"
    side = json.loads(side_path.read_text())
    side["expert_notes"] = {"inspections": [{"object": "x", "frame": 20, "decision": "place on the red pad"}]}
    side_path.write_text(json.dumps(side | sidecar))
    return copy


def test_decision_place_names_where_the_decided_object_lies_among_its_kind(vlm, root, tmp_path):
    """--policy.decision_place: the think=decision target names the decided pad by its place among the
    pads by azimuth (larger angle: further left); --policy.decision_layout lists every pad's place before
    it; a decision that names no placed object is refused."""
    pads = {"blue_pad": 25.5, "green_pad": 83.0, "red_pad": 107.2}
    placements = [{"name": n, "category": "color_pad", "r": 0.4, "angle": a} for n, a in pads.items()]
    placements.append({"name": "bell", "category": "bell", "r": 0.5, "angle": 200.0})
    copy = _with_red_pad_reading(root, tmp_path, placements=placements)
    ann = DatasetAnnotations(copy, REPO)
    assert (
        ann.subtask_and_decision(40, place=True) == f"{ann.subtask(40)}; place on the red pad, the left one"
    )
    assert ann.subtask_and_decision(40) == f"{ann.subtask(40)}; place on the red pad"
    places = [ann.place_of(0, f"place on the {c} pad") for c in ("blue", "green", "red")]
    assert places == ["right", "middle", "left"]
    assert ann.subtask_and_decision(10, place=True) == ann.subtask(10)  # nothing read yet
    assert ann.subtask_and_decision(40, place=True, layout=True) == (
        f"{ann.subtask(40)}; blue pad right, green pad middle, red pad left; place on the red pad, the left one"
    )
    with pytest.raises(ValueError, match="yellow_pad, which is not among"):
        ann.place_of(0, "place on the yellow pad")

    _, _, pre, _, ds = _setup(vlm, copy, memory="chunk", history=2, think="decision", decision_place=True)
    _, _, plain_pre, _, _ = _setup(vlm, copy, memory="chunk", history=2, think="decision")
    tok = lambda b: b[THINK_IDS][0][b[THINK_MASK][0]].tolist()  # noqa: E731
    placed, plain = tok(collate(ds, pre, [40])), tok(collate(ds, plain_pre, [40]))
    assert len(placed) > len(plain) and placed[: len(plain) - 2] == plain[:-2]  # the place follows
    laid_cfg, laid_policy, laid_pre, _, _ = _setup(
        vlm,
        copy,
        memory="chunk",
        history=2,
        think="decision",
        think_first=True,
        decision_place=True,
        decision_layout=True,
    )
    laid_batch = collate(ds, laid_pre, [40])
    laid = tok(laid_batch)
    assert len(laid) > len(placed) and laid[-len(placed) + len(plain) - 2 :] == placed[len(plain) - 2 :]
    # a span that evaluation decodes (think_first) and that is longer than the decoding budget is refused
    # in training, naming the budget it needs; a span after the queries is never decoded
    needed = len(laid) - 2  # the target and </think>, without <think> and the end of turn
    laid_policy.train()
    laid_cfg.subtask_max_tokens = needed - 1
    with pytest.raises(ValueError, match=f"Set --policy.subtask_max_tokens to at least {needed}"):
        laid_policy.forward(laid_batch)
    laid_cfg.think_first = False
    assert torch.isfinite(laid_policy.forward(laid_batch)[0])
    laid_cfg.think_first, laid_cfg.subtask_max_tokens = True, needed
    assert torch.isfinite(laid_policy.forward(laid_batch)[0])
    with pytest.raises(ValueError, match="set --policy.think=decision"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), think="subtask", decision_place=True)
    with pytest.raises(ValueError, match="set --policy.decision_place=true"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), think="decision", decision_layout=True)


def test_decision_where_says_where_the_object_to_act_on_lies(vlm, root, tmp_path):
    """--policy.decision_where: the pick's frames before the reading name where the inspected object
    lies, the decision ends with where its pad lies (cm and degrees from the base, rounded); the frames
    of later subtasks before the reading name nothing more; the annotation step writes it."""
    placements = [
        {"name": "blue_pad", "category": "color_pad", "r": 0.3579, "angle": 25.55},
        {"name": "red_pad", "category": "color_pad", "r": 0.3675, "angle": 107.21},
        {"name": "gray_block", "category": "patch_block", "r": 0.4022, "angle": 54.44},
    ]
    notes = {"inspections": [{"object": "gray_block", "frame": 20, "decision": "place on the red pad"}]}
    copy = _with_red_pad_reading(root, tmp_path, placements=placements, expert_notes=notes)
    ann = DatasetAnnotations(copy, REPO)
    sub = ann.cols["subtask_index"]
    first = min(ann.subtask_text[0])
    picking = [i for i in range(20) if sub[i] == first]
    assert picking, "the fixture's episode 0 starts with its first subtask"
    for i in picking:
        assert ann.subtask_and_decision(i, where_=True) == f"{ann.subtask(i)}; gray block at 40 cm, 54 deg"
        assert ann.subtask_and_decision(i) == ann.subtask(i)
    for i in [i for i in range(20) if sub[i] != first]:
        assert ann.subtask_and_decision(i, where_=True) == ann.subtask(i)
    assert ann.subtask_and_decision(40, place=True, where_=True) == (
        f"{ann.subtask(40)}; place on the red pad, the left one at 37 cm, 107 deg"
    )
    assert ann.subtask_and_decision(40, place=True, layout=True, where_=True).endswith(
        "blue pad right, red pad left; place on the red pad, the left one at 37 cm, 107 deg"
    )
    missing = [p for p in placements if p["name"] != "red_pad"]
    with pytest.raises(ValueError, match="red_pad, which is not among"):
        decision_clause(missing, "place on the red pad", where_=True)

    _, policy, pre, _, ds = _setup(
        vlm, copy, memory="chunk", history=2, think="decision", decision_where=True
    )
    batch = collate(ds, pre, [picking[0], 40])
    spans = [
        policy.text_tokenizer.decode(ids[mask].tolist())
        for ids, mask in zip(batch[THINK_IDS], batch[THINK_MASK], strict=True)
    ]
    assert "gray block at 40 cm, 54 deg" in spans[0] and "red pad at 37 cm, 107 deg" in spans[1]
    with pytest.raises(ValueError, match="set --policy.think=decision"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), think="subtask", decision_where=True)


def test_decision_weight_weighs_the_frames_where_the_expert_acts_on_a_reading(vlm, root, tmp_path):
    """--policy.decision_weight: the first decision_window frames of every subtask that begins after the
    episode's first reading weigh that much in the action loss; a build without readings is refused."""
    from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import ACTION_WEIGHT

    copy = _with_red_pad_reading(root, tmp_path, episode=1)  # the count episode: 2 subtasks
    ann = DatasetAnnotations(copy, REPO)
    onsets = ann.decision_onsets(window=8)
    frames, subtasks = ann.cols["frame_index"], ann.cols["subtask_index"]
    expected, since = [], None
    for i in range(ann.ep_start[1], ann.ep_end[1]):  # episode 1, frame by frame
        if i == ann.ep_start[1] or subtasks[i] != subtasks[i - 1]:
            since = 0 if frames[i] >= 20 else None
        elif since is not None:
            since += 1
        expected.append(since is not None and since < 8)
    assert onsets[ann.ep_start[1] : ann.ep_end[1]].tolist() == expected and sum(expected) == 8
    assert not onsets[: ann.ep_start[1]].any()  # the first episode read nothing
    onset, other = int(np.flatnonzero(onsets)[0]), int(np.flatnonzero(onsets)[0]) - 1

    cfg, policy, pre, _, ds = _setup(
        vlm, copy, memory="chunk", history=2, think="none", decision_weight=5.0, decision_window=8
    )
    batch = collate(ds, pre, [onset, other])
    assert batch[ACTION_WEIGHT].tolist() == [5.0, 1.0]
    plain = {k: v for k, v in batch.items() if k != ACTION_WEIGHT}
    policy.eval()
    with torch.no_grad():
        per_sample = policy.forward(plain, reduction="none")[0]
        weighted = policy.forward(batch)[0]
    assert torch.allclose(weighted, (5 * per_sample[0] + per_sample[1]) / 6)
    assert not torch.allclose(weighted, per_sample.mean())
    policy.train()  # training on batches of a preprocessor without the weights (an older checkpoint's)
    with pytest.raises(ValueError, match="carries no action weights"):
        policy.forward(plain)
    _, _, unread_pre, _, unread_ds = _setup(
        vlm, root, memory="chunk", history=2, think="none", decision_weight=5.0
    )
    with pytest.raises(ValueError, match="holds none"):
        collate(unread_ds, unread_pre, [onset])
    with pytest.raises(ValueError, match="decision_weight must be > 0"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), decision_weight=0.0)


def test_opening_weight_weighs_every_episodes_first_frames(vlm, root, tmp_path):
    """--policy.opening_weight: every episode's first opening_window frames weigh that much in the
    action loss, multiplying decision_weight's at a decision onset; no readings needed without it."""
    from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import ACTION_WEIGHT

    ann = DatasetAnnotations(root, REPO)
    first, late = int(ann.ep_start[1]), int(ann.ep_start[1]) + 5  # episode 1's frames 0 and 5
    _, policy, pre, _, ds = _setup(
        vlm, root, memory="chunk", history=2, think="none", opening_weight=3.0, opening_window=5
    )
    batch = collate(ds, pre, [first, late - 1, late])
    assert batch[ACTION_WEIGHT].tolist() == [3.0, 3.0, 1.0]
    copy = _with_red_pad_reading(root, tmp_path, episode=1)
    onset = int(np.flatnonzero(DatasetAnnotations(copy, REPO).decision_onsets(window=8))[0])
    weights = {"decision_weight": 5.0, "decision_window": 8, "opening_weight": 3.0}
    _, _, both, _, both_ds = _setup(
        vlm, copy, memory="chunk", history=2, think="none", opening_window=onset - first + 1, **weights
    )
    assert collate(both_ds, both, [onset, first, late])[ACTION_WEIGHT].tolist() == [15.0, 3.0, 3.0]
    policy.train()
    with pytest.raises(
        ValueError, match="opening_weight=3.0 / --policy.miss_weight=1.0, but the batch carries no"
    ):
        policy.forward({k: v for k, v in batch.items() if k != ACTION_WEIGHT})
    with pytest.raises(ValueError, match="opening_weight must be > 0"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), opening_weight=0.0)


def test_miss_weight_leaves_out_a_grasp_retry_builds_missed_tries(vlm, root, tmp_path):
    """--policy.miss_weight: the frames of a missed try (the sidecar's expert_notes.grasp_misses,
    [from, to)) weigh that much in the action loss, 0 leaving them out; a batch of such frames alone
    adds no action loss; a build without missed tries, or a negative weight, is refused."""
    from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import ACTION_WEIGHT

    copy = _with_red_pad_reading(root, tmp_path, episode=1)
    side_path = copy / "meta/activearena/sidecars/episode_000001.json"
    side = json.loads(side_path.read_text())
    side["expert_notes"]["grasp_misses"] = [[3, 7]]
    side_path.write_text(json.dumps(side))
    first = int(DatasetAnnotations(copy, REPO).ep_start[1])
    _, policy, pre, _, ds = _setup(vlm, copy, memory="chunk", history=2, think="none", miss_weight=0.0)
    batch = collate(ds, pre, [first + 2, first + 3, first + 6, first + 7])
    assert batch[ACTION_WEIGHT].tolist() == [1.0, 0.0, 0.0, 1.0]
    policy.train()
    missed = collate(ds, pre, [first + 4, first + 5])
    loss, info = policy.forward(missed)  # think=none: the action loss alone
    assert float(loss) == 0.0 and info["l1_loss"] > 0  # unweighted it is not 0
    _, _, plain_pre, _, plain_ds = _setup(vlm, root, memory="chunk", history=2, think="none", miss_weight=0.0)
    with pytest.raises(ValueError, match="holds none"):
        collate(plain_ds, plain_pre, [first])
    with pytest.raises(ValueError, match="miss_weight must be >= 0"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), miss_weight=-1.0)


def test_decision_think_appends_the_read_decision_from_the_frame_it_was_read_on(vlm, root, tmp_path):
    """think=decision: the subtask text, then from the inspection's frame on the decision the expert
    took from it (an inspect-and-place episode's ``expert_notes``); before it the plain subtask."""
    copy = _with_red_pad_reading(root, tmp_path)
    ann = DatasetAnnotations(copy, REPO)
    assert ann.decision(19) is None and ann.subtask_and_decision(19) == ann.subtask(19)
    assert ann.decision(20) == ann.decision(40) == "place on the red pad"
    assert ann.subtask_and_decision(40) == f"{ann.subtask(40)}; place on the red pad"
    other = int(ann.ep_start[1])  # the second episode read nothing
    assert ann.subtask_and_decision(other + 40) == ann.subtask(other + 40)

    _, _, pre, _, ds = _setup(vlm, copy, memory="chunk", history=2, think="decision")
    _, _, pre_subtask, _, _ = _setup(vlm, copy, memory="chunk", history=2, think="subtask")
    early, late = collate(ds, pre, [10, 40]), collate(ds, pre_subtask, [10, 40])
    decided = collate(ds, pre, [40, 10])
    span = lambda b, i: b[THINK_IDS][i][b[THINK_MASK][i]].tolist()  # noqa: E731
    assert span(early, 0) == span(late, 0)  # frame 10: nothing read yet, the subtask alone
    assert len(span(decided, 0)) > len(span(late, 1))  # frame 40: the decision follows the subtask
    n = len(span(late, 1)) - 2  # the subtask span less its closing </think><|im_end|>
    assert span(decided, 0)[:n] == span(late, 1)[:n]  # the subtask first, then the decision


def test_decision_token_weight_weighs_the_decision_clause_in_the_lm_loss(vlm, root, tmp_path):
    """--policy.decision_token_weight: the targets after the span's last ";" (the decision clause) weigh
    that much in the LM loss; a span without a decision is a plain mean."""
    copy = _with_red_pad_reading(root, tmp_path)
    _, policy, pre, _, ds = _setup(
        vlm, copy, memory="chunk", history=2, think="decision", decision_token_weight=5.0
    )
    batch = collate(ds, pre, [40])  # frame 40: after the reading
    ids, mask = batch[THINK_IDS], batch[THINK_MASK]
    weights = policy.think_token_weights(ids, mask)[0][mask[0]]
    heavy = ids[0][mask[0]][weights == 5.0].tolist()
    assert policy.text_tokenizer.decode(heavy) == " place on the red pad</think><|im_end|>"
    assert (weights[weights != 5.0] == 1.0).all()
    early = collate(ds, pre, [10])  # nothing read yet: no decision clause
    assert (policy.think_token_weights(early[THINK_IDS], early[THINK_MASK]) == 1.0).all()

    policy.eval()

    def lm_loss(weight: float) -> float:
        policy.config.decision_token_weight = weight
        with torch.no_grad():
            return policy.forward(batch)[1]["lm_loss"]

    # L(w) = (n_a a + w n_d d) / (n_a + w n_d): the clause's n_d targets at mean loss d, the n_a others at a
    n_d, n_a = len(heavy), int(mask.sum()) - 1 - len(heavy)
    plain, five = lm_loss(1.0), lm_loss(5.0)
    d = (five * (n_a + 5 * n_d) - plain * (n_a + n_d)) / (4 * n_d)
    a = (plain * (n_a + n_d) - n_d * d) / n_a
    assert abs(plain - five) > 1e-4  # the weighting changes the loss
    assert lm_loss(20.0) == pytest.approx((n_a * a + 20 * n_d * d) / (n_a + 20 * n_d), rel=1e-4)
    with pytest.raises(ValueError, match="decision_token_weight weighs the decision clause"):
        ActiveArenaOFTConfig(vlm_path=str(vlm), think="subtask", decision_token_weight=5.0)
