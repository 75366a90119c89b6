"""Training with a frozen vision tower and a vision cache (``activearena-cache-vision``): the chunk memory's
frames read from the table give the loss and gradients of decoding them and running the tower, the
dataset then decodes the current frame only, a table of another tower or image size is refused, and the
preset pair trains through lerobot-train."""

import json
from pathlib import Path

import pytest
import torch
from helpers.params import DATASET_REPO as REPO
from helpers.policy_runs import build_policy, collate, train_preset
from safetensors import safe_open

from lerobot_activearena.cli.cache_vision import main as cache_vision
from lerobot_activearena.policies.activearena_oft.configuration_activearena_oft import ActiveArenaOFTConfig
from lerobot_activearena.policies.activearena_vla.helpers import blank_memory_pixels
from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import (
    FRAME_VALID,
    GRID,
    MEMORY_INDEX,
    PIXELS,
)
from lerobot_activearena.policies.activearena_vla.vlm_loading import load_policy_vlm

CONFIGS = Path(__file__).resolve().parents[2] / "configs" / "policy"
MEMORY_KEYS = {
    "memory",
    "history",
    "vision_cache",
}  # where a chunk-12 preset and its memory-free partner differ


def differing_policy_keys(a: dict, b: dict) -> set[str]:
    """The policy keys whose values differ between two presets."""
    return {k for k in set(a["policy"]) | set(b["policy"]) if a["policy"].get(k) != b["policy"].get(k)}


def small_preset(memory: str, name: str) -> dict:
    """``configs/policy/small/oft_subtask_<memory>_ws_grounded_<name>.json``."""
    return json.loads((CONFIGS / "small" / f"oft_subtask_{memory}_ws_grounded_{name}.json").read_text())


PIXELS_96 = 96 * 128


@pytest.fixture(scope="module")
def table(tiny_vlm, bell_count_dataset, tmp_path_factory):
    out = tmp_path_factory.mktemp("vision_cache") / "tiny.safetensors"
    cache_vision(
        [str(tiny_vlm), "--root", str(bell_count_dataset), "--repo-id", REPO, "--out", str(out)]
        + ["--image-max-pixels", str(PIXELS_96)]
    )
    return out


def _config(vlm, **overrides):
    settings = {
        "memory": "chunk",
        "history": 4,
        "think": "subtask",
        "freeze_vision": True,
        "image_max_pixels": PIXELS_96,
    }
    return ActiveArenaOFTConfig(vlm_path=str(vlm), device="cpu", state_hidden=32, **(settings | overrides))


def test_cached_memory_gives_the_loss_and_gradients_of_decoding_it(tiny_vlm, bell_count_dataset, table):
    live_cfg, cached_cfg = _config(tiny_vlm), _config(tiny_vlm, vision_cache=str(table))
    assert cached_cfg.observation_delta_indices is None  # LeRobot reads the current frame only
    live, live_pre, _, live_ds = build_policy(live_cfg, bell_count_dataset)
    cached, cached_pre, _, cached_ds = build_policy(cached_cfg, bell_count_dataset)
    indices = [3, 70, len(live_ds) - 40]  # the first one's memory is mostly before the episode start
    a, b = collate(live_ds, live_pre, indices), collate(cached_ds, cached_pre, indices)
    assert torch.equal(a[FRAME_VALID], b[FRAME_VALID]) and not bool(a[FRAME_VALID][0].all())
    assert torch.allclose(a["observation.state"][a[FRAME_VALID]], b["observation.state"][b[FRAME_VALID]])
    assert len(b[PIXELS]) == len(indices) < len(a[PIXELS])  # pixels of the current frames only
    assert b[MEMORY_INDEX].shape == (3, 4) and int(b[MEMORY_INDEX][1, -1]) == 70 - 16
    loss_a, _ = live.forward(a)
    loss_b, _ = cached.forward(b)
    assert torch.allclose(loss_a, loss_b, atol=1e-5)
    loss_a.backward()
    loss_b.backward()
    params_a, params_b = dict(live.named_parameters()), dict(cached.named_parameters())
    for name in (
        "action_queries",
        "state_encoder.frame.weight",
        "vlm.model.language_model.layers.0.mlp.up_proj.weight",
    ):
        assert torch.allclose(params_a[name].grad, params_b[name].grad, atol=1e-5, rtol=1e-4), name
    frozen = [p for n, p in cached.named_parameters() if n.startswith("vlm.model.visual.")]
    assert frozen and all(p.grad is None and not p.requires_grad for p in frozen)
    optimised = {id(p) for g in cached.get_optim_params() for p in g["params"]}
    assert not any(id(p) in optimised for p in frozen)


def test_a_frozen_memory_tower_lets_the_current_frames_tower_train_beside_the_cache(
    tiny_vlm, bell_count_dataset, table
):
    """memory_vision=frozen: the memory frames go through a frozen copy of the tower as loaded, so the
    table made from that tower still holds their features once the policy's own tower (which reads the
    current frame) has trained away from it; the cached batch gives the loss and gradients of decoding
    the memory, the copy gets none, and vision_lr sets the trained tower's own rate."""
    tuned = {"freeze_vision": False, "memory_vision": "frozen", "vision_lr": 1e-5}
    live_cfg, cached_cfg = _config(tiny_vlm, **tuned), _config(tiny_vlm, vision_cache=str(table), **tuned)
    live, live_pre, _, live_ds = build_policy(live_cfg, bell_count_dataset)
    cached, cached_pre, _, cached_ds = build_policy(cached_cfg, bell_count_dataset)
    shared, shared_pre, _, _ = build_policy(_config(tiny_vlm, freeze_vision=False), bell_count_dataset)
    for policy in (live, cached, shared):
        with torch.no_grad():  # as after training steps: the policy's tower moved, the copy did not
            torch.manual_seed(1)
            for p in policy.vlm.model.visual.parameters():
                p.add_(0.05 * torch.randn_like(p))
    indices = [70, len(live_ds) - 40]
    a, b = collate(live_ds, live_pre, indices), collate(cached_ds, cached_pre, indices)
    loss_a, _ = live.forward(a)
    loss_b, _ = cached.forward(b)
    assert torch.allclose(loss_a, loss_b, atol=1e-5)
    # the shared tower reads the memory through the moved weights: another loss
    assert not torch.allclose(shared.forward(collate(live_ds, shared_pre, indices))[0], loss_a, atol=1e-4)
    loss_a.backward()
    loss_b.backward()
    params_a, params_b = dict(live.named_parameters()), dict(cached.named_parameters())
    for name in ("vlm.model.visual.blocks.0.mlp.linear_fc1.weight", "action_queries"):
        assert params_a[name].grad is not None and params_a[name].grad.abs().sum() > 0, name
        assert torch.allclose(params_a[name].grad, params_b[name].grad, atol=1e-5, rtol=1e-4), name
    copy = [p for n, p in cached.named_parameters() if n.startswith("memory_tower.")]
    assert copy and all(p.grad is None and not p.requires_grad for p in copy)
    groups = cached.get_optim_params()
    assert [g["lr"] for g in groups] == [cached_cfg.optimizer_lr, 1e-5, cached_cfg.head_lr]
    assert {id(p) for p in groups[1]["params"]} == {id(p) for p in cached.vlm.model.visual.parameters()}
    assert not {id(p) for g in groups for p in g["params"]} & {id(p) for p in copy}


def test_the_current_frame_at_more_tokens_reads_its_memory_from_the_same_table(
    tiny_vlm, bell_count_dataset, table
):
    """current_image_pixels: the current frame read at 4x the memory frames' pixels (4x their tokens),
    the memory frames at image_max_pixels, so the table made at that size still holds them: decoding
    the memory from the dataset's images (the frames packed at two sizes) and reading it from the table
    give one loss, and the current frame's tokens differ from those of one size for all."""
    bigger = {"current_image_pixels": 4 * PIXELS_96, "freeze_vision": False, "memory_vision": "frozen"}
    live, live_pre, _, live_ds = build_policy(_config(tiny_vlm, **bigger), bell_count_dataset)
    cached, cached_pre, _, cached_ds = build_policy(
        _config(tiny_vlm, vision_cache=str(table), **bigger), bell_count_dataset
    )
    indices = [3, 70, len(live_ds) - 40]
    a, b = collate(live_ds, live_pre, indices), collate(cached_ds, cached_pre, indices)
    tokens_a, tokens_b = a[GRID].prod(-1), b[GRID].prod(-1)
    assert torch.equal(tokens_a[a[FRAME_VALID]], tokens_b[b[FRAME_VALID]])
    with safe_open(str(table), "pt") as f:
        table_tokens = int(torch.tensor(json.loads(f.metadata()["meta"])["grid"]).prod())
    assert (tokens_b[:, :-1] == table_tokens).all() and (tokens_b[:, -1] == 4 * table_tokens).all()
    # the live batch packs its frames of two sizes as one (patches, dim) run
    assert a[PIXELS].dim() == 2 and len(a[PIXELS]) == int(tokens_a[a[FRAME_VALID]].sum())
    assert b[PIXELS].shape[:2] == (3, 4 * table_tokens)
    blank = blank_memory_pixels(a[PIXELS], a[FRAME_VALID], a[GRID])  # the memory rows gray, the current kept
    sizes = tokens_a[a[FRAME_VALID]].tolist()
    current = a[FRAME_VALID].nonzero()[:, 1] == a[FRAME_VALID].shape[1] - 1
    for row, blank_row, is_current in zip(a[PIXELS].split(sizes), blank.split(sizes), current, strict=True):
        assert torch.equal(blank_row, row) if is_current else not blank_row.any()
    loss_a, _ = live.forward(a)
    loss_b, _ = cached.forward(b)
    assert torch.allclose(loss_a, loss_b, atol=1e-5)
    _, plain_pre, _, plain_ds = build_policy(_config(tiny_vlm, vision_cache=str(table)), bell_count_dataset)
    assert (collate(plain_ds, plain_pre, indices)[GRID].prod(-1) == table_tokens).all()


def test_a_cache_of_another_tower_or_image_size_is_refused(tiny_vlm, bell_count_dataset, table):
    policy, pre, _, ds = build_policy(_config(tiny_vlm, vision_cache=str(table)), bell_count_dataset)
    batch = collate(ds, pre, [70])
    with torch.no_grad():
        next(policy.vlm.model.visual.parameters()).add_(0.01)  # no longer the tower the table came from
    with pytest.raises(ValueError, match="different vision tower.*activearena-cache-vision"):
        policy.forward(batch)
    policy, pre, _, ds = build_policy(
        _config(tiny_vlm, vision_cache=str(table), image_max_pixels=2 * PIXELS_96), bell_count_dataset
    )
    with pytest.raises(ValueError, match="image_max_pixels=12288.*--image-max-pixels 24576"):
        policy.forward(collate(ds, pre, [70]))


def test_vision_cache_settings_that_cannot_work_are_named(tiny_vlm, table, tmp_path):
    with pytest.raises(ValueError, match="freeze_vision=true or --policy.memory_vision=frozen"):
        _config(tiny_vlm, vision_cache=str(table), freeze_vision=False)
    with pytest.raises(ValueError, match="memory=chunk"):
        _config(tiny_vlm, vision_cache=str(table), memory="none")
    with pytest.raises(SystemExit):  # an existing table is kept
        cache_vision([str(tiny_vlm), "--root", str(tmp_path), "--repo-id", REPO, "--out", str(table)])


def test_the_frozen_count_pair_trains_through_lerobot_train(tiny_vlm, bell_count_dataset, table, tmp_path):
    small = CONFIGS / "small"
    chunk = json.loads((small / "oft_subtask_action_12_ws_grounded_count_frozen.json").read_text())
    free = json.loads((small / "oft_subtask_no_0_ws_grounded_count_frozen.json").read_text())
    base = json.loads((small / "oft_subtask_action_12_ws_grounded_count.json").read_text())
    # the frozen tower and its table, and the frozen pair's own shorter, faster schedule
    assert {k for k in chunk["policy"] if chunk["policy"][k] != base["policy"].get(k)} == {
        "freeze_vision",
        "vision_cache",
        "optimizer_lr",
        "head_lr",
        "scheduler_warmup_steps",
        "scheduler_decay_steps",
    }
    assert (chunk["steps"], chunk["batch_size"]) == (free["steps"], free["batch_size"])
    assert differing_policy_keys(chunk, free) == MEMORY_KEYS
    for name, extra in (
        ("oft_subtask_action_12_ws_grounded_count_frozen", [f"--policy.vision_cache={table}"]),
        ("oft_subtask_no_0_ws_grounded_count_frozen", []),
    ):
        ckpt = train_preset(
            small / f"{name}.json",
            bell_count_dataset,
            tiny_vlm,
            tmp_path / name,
            f"--policy.image_max_pixels={PIXELS_96}",
            *extra,
        )
        saved = json.loads((ckpt / "config.json").read_text())
        assert saved["freeze_vision"] is True


def test_the_one_arm_count_pair_is_the_frozen_pair_on_its_own_build():
    """The _count_left_frozen pair: the frozen count pair on the one-arm build (``--press-arm left``),
    read through the tower grounded on that build and its table, 2,000 steps; the two still differ
    only in the memory, and LeRobot parses both."""
    from lerobot.configs.train import TrainPipelineConfig

    small = CONFIGS / "small"
    pair = {}
    for memory in ("action_12", "no_0"):
        left = pair[memory] = small_preset(memory, "count_left_frozen")
        frozen = small_preset(memory, "count_frozen")
        assert left["dataset"] == {**frozen["dataset"], "repo_id": "local/cpu_count_left_200_p16_192"}
        changed = {k for k in left["policy"] if left["policy"][k] != frozen["policy"].get(k)}
        assert changed == {"vlm_path", "scheduler_decay_steps"} | (
            {"vision_cache"} if memory == "action_12" else set()
        )
        assert left["policy"]["vlm_path"] == "outputs/small_vlm_v256d4_p32_grounded_count_left"
        assert left["steps"] == left["policy"]["scheduler_decay_steps"] == 2000
        cfg = TrainPipelineConfig.from_pretrained(
            small / f"oft_subtask_{memory}_ws_grounded_count_left_frozen.json"
        )
        assert cfg.policy.freeze_vision and cfg.dataset.repo_id == "local/cpu_count_left_200_p16_192"
    chunk, free = pair["action_12"], pair["no_0"]
    assert differing_policy_keys(chunk, free) == MEMORY_KEYS
    assert {k for k in chunk if chunk[k] != free[k]} == {"policy", "job_name"}


def test_the_object_grounded_pair_is_the_one_arm_pair_on_its_own_tower():
    """The _count_left_objects_frozen pair: the one-arm pair read through a tower grounded also on the
    blocks to count and on which object each token holds (``activearena-ground-vision --search-weight
    --identity-weight``) and that tower's table; nothing else changed, and the two still differ only
    in the memory."""
    pair = {}
    for memory in ("action_12", "no_0"):
        objects = pair[memory] = small_preset(memory, "count_left_objects_frozen")
        left = small_preset(memory, "count_left_frozen")
        assert {k for k in objects if objects[k] != left[k]} == {"policy", "job_name"}
        assert differing_policy_keys(objects, left) == {"vlm_path"} | (
            {"vision_cache"} if memory == "action_12" else set()
        )
        assert objects["policy"]["vlm_path"] == "outputs/small_vlm_v256d4_p32_grounded_count_left_objects"
    chunk, free = pair["action_12"], pair["no_0"]
    assert differing_policy_keys(chunk, free) == MEMORY_KEYS
    assert chunk["policy"]["vision_cache"].endswith("_grounded_objects.safetensors")


TUNED = "oft_subtask_action_12_ws_grounded_count_left_objects_tuned"


@pytest.fixture(scope="module")
def tuned_checkpoint(tiny_vlm, bell_count_dataset, table, tmp_path_factory):
    """The tuned chunk-12 preset through lerobot-train on the table: a checkpoint whose memory tower is
    a frozen copy and whose training batches held the current frame only."""
    return train_preset(
        CONFIGS / "small" / f"{TUNED}.json",
        bell_count_dataset,
        tiny_vlm,
        tmp_path_factory.mktemp(TUNED) / "run",
        f"--policy.image_max_pixels={PIXELS_96}",
        f"--policy.vision_cache={table}",
    )


def test_the_tuned_pair_trains_the_current_frames_tower_and_keeps_the_memorys(tiny_vlm, tuned_checkpoint):
    """The _count_left_objects_tuned pair: the object-grounded pair with the vision tower trained (at
    vision_lr) on the current frame; the chunk-12 one reads its memory through a frozen copy of the
    grounded tower (and that tower's table). The two still differ only in the memory; the chunk-12
    one trains through lerobot-train and its checkpoint keeps the copy as loaded."""
    from safetensors.torch import load_file

    pair = {}
    for memory in ("action_12", "no_0"):
        tuned = pair[memory] = small_preset(memory, "count_left_objects_tuned")
        frozen = small_preset(memory, "count_left_objects_frozen")
        assert {k for k in tuned if tuned[k] != frozen[k]} == {"policy", "job_name"}
        assert differing_policy_keys(tuned, frozen) == {"freeze_vision", "vision_lr"} | (
            {"memory_vision"} if memory == "action_12" else set()
        )
        assert tuned["policy"]["freeze_vision"] is False and tuned["policy"]["vision_lr"] == 1e-4
    chunk, free = pair["action_12"], pair["no_0"]
    assert differing_policy_keys(chunk, free) == MEMORY_KEYS | {"memory_vision"}
    weights = load_file(str(tuned_checkpoint / "model.safetensors"))
    original = load_policy_vlm(str(tiny_vlm), torch.float32, "sdpa").model.visual.state_dict()
    copies = {k.removeprefix("memory_tower."): v for k, v in weights.items() if k.startswith("memory_tower.")}
    assert copies and copies.keys() == original.keys()
    assert all(torch.equal(copies[k], original[k]) for k in copies)
    trained = {
        k.removeprefix("vlm.model.visual."): v
        for k, v in weights.items()
        if k.startswith("vlm.model.visual.")
    }
    assert any(not torch.equal(trained[k], original[k]) for k in original)


def test_scoring_dataset_frames_reads_a_table_policys_memory_as_images(tuned_checkpoint, bell_count_dataset):
    """A policy trained on a vision table, scored on dataset frames (decision probe, open-loop error):
    its history comes as images through its memory tower and gives the action-query states of the
    training path (memory from the table); the current frame alone gives others."""
    from helpers.analysis_scripts import load
    from lerobot.configs.policies import PreTrainedConfig

    from lerobot_activearena.policies.activearena_vla.modeling_activearena_vla import QUERY

    indices = [70, 120]
    states, _, _ = load("analysis/policies/decision_probe.py").features(
        tuned_checkpoint, REPO, bell_count_dataset, indices
    )
    cfg = PreTrainedConfig.from_pretrained(tuned_checkpoint)
    assert cfg.vision_cache  # the training path: the table by frame index
    cfg.device, cfg.pretrained_path = "cpu", tuned_checkpoint
    policy, pre, _, ds = build_policy(cfg, bell_count_dataset)
    policy.eval()
    batch = collate(ds, pre, indices)
    assert batch[MEMORY_INDEX].shape == (2, 12) and len(batch[PIXELS]) == 2

    def query_states(b, cache):
        with torch.no_grad():
            h, kind, _ = policy.hidden_states(*policy.training_args(b), vision_cache=cache)
        return h[kind == QUERY].view(len(indices), -1, h.shape[-1]).float().mean(1).numpy()

    trained = query_states(batch, policy.cached_memory(batch))
    current_only = dict(batch)
    current_only[FRAME_VALID] = torch.zeros_like(batch[FRAME_VALID])
    current_only[FRAME_VALID][:, -1] = True
    alone = query_states(current_only, {})
    gap = float(abs(states - trained).max())
    assert gap < 0.05 * float(abs(alone - trained).max()), (gap, float(abs(alone - trained).max()))


def test_the_wos_pair_is_the_tuned_pair_without_state_tokens_at_batch_64():
    """The paper's `wos` variant of the _count_left_objects_tuned pair: no state tokens and batch 64,
    nothing else changed; the two of the pair still differ only in the memory, and LeRobot parses both
    with the state off."""
    from lerobot.configs.train import TrainPipelineConfig

    pair = {}
    for memory in ("action_12", "no_0"):
        path = CONFIGS / "small" / f"oft_subtask_{memory}_wos_grounded_count_left_objects_tuned.json"
        wos = pair[memory] = json.loads(path.read_text())
        ws = small_preset(memory, "count_left_objects_tuned")
        assert {k for k in wos if wos[k] != ws[k]} == {"policy", "batch_size", "job_name"}
        assert differing_policy_keys(wos, ws) == {"use_state"}
        assert wos["batch_size"] == 64 and ws["batch_size"] == 32
        assert "_wos_" in wos["job_name"]
        cfg = TrainPipelineConfig.from_pretrained(path)
        assert cfg.policy.use_state is False and cfg.batch_size == 64
    chunk, free = pair["action_12"], pair["no_0"]
    assert differing_policy_keys(chunk, free) == MEMORY_KEYS | {"memory_vision"}
    assert {k for k in chunk if chunk[k] != free[k]} == {"policy", "job_name"}


def test_the_block_pair_is_the_tuned_count_pair_on_the_block_build_at_batch_64():
    """The _block_readings_tuned pair (check_block_color, IA): the tuned count pair moved to the block
    build, a tower grounded on its objects and on the block's back colour where the expert reads it
    (``activearena-ground-vision --reading-window``) and that tower's table, at batch 64; nothing else
    changed, and the two still differ only in the memory."""
    from lerobot.configs.train import TrainPipelineConfig

    pair = {}
    for memory in ("action_12", "no_0"):
        path = CONFIGS / "small" / f"oft_subtask_{memory}_ws_grounded_block_readings_tuned.json"
        block = pair[memory] = json.loads(path.read_text())
        count = small_preset(memory, "count_left_objects_tuned")
        assert {k for k in block if block[k] != count[k]} == {"dataset", "policy", "batch_size", "job_name"}
        assert block["dataset"] == {**count["dataset"], "repo_id": "local/cpu_block_200_p16_192"}
        assert differing_policy_keys(block, count) == {"vlm_path"} | (
            {"vision_cache"} if memory == "action_12" else set()
        )
        assert block["policy"]["vlm_path"] == "outputs/small_vlm_v256d4_p32_grounded_block_readings"
        cfg = TrainPipelineConfig.from_pretrained(path)
        assert cfg.batch_size == 64 and cfg.policy.use_state
    chunk, free = pair["action_12"], pair["no_0"]
    assert differing_policy_keys(chunk, free) == MEMORY_KEYS | {"memory_vision"}
    assert chunk["policy"]["vision_cache"] == (
        "outputs/vision_cache/cpu_block_200_p16_192_grounded_readings.safetensors"
    )
    assert {k for k in chunk if chunk[k] != free[k]} == {"policy", "job_name"}


def test_the_decision_pair_is_the_block_pair_with_the_read_decision_in_its_think_target():
    """``oft_decision_*_block_readings_tuned``: the block pair with ``think=decision`` (the subtask text
    and, once the patch is read, the expert's decision), nothing else changed."""
    from lerobot.configs.train import TrainPipelineConfig

    for memory in ("action_12", "no_0"):
        block = json.loads(
            (CONFIGS / "small" / f"oft_subtask_{memory}_ws_grounded_block_readings_tuned.json").read_text()
        )
        name = f"oft_decision_{memory}_ws_grounded_block_readings_tuned"
        decision = json.loads((CONFIGS / "small" / f"{name}.json").read_text())
        assert {k for k in block if block[k] != decision[k]} == {"policy", "job_name"}
        assert differing_policy_keys(decision, block) == {"think"}
        assert decision["job_name"] == f"small_{name}"
        assert (
            TrainPipelineConfig.from_pretrained(CONFIGS / "small" / f"{name}.json").policy.think == "decision"
        )


def test_the_think_first_pair_is_the_decision_pair_with_its_span_before_the_actions():
    """``oft_decision_*_block_readings_tuned_think_first``: the decision pair with ``think_first`` (the
    actions read the span, decoded by the policy at evaluation), nothing else changed."""
    from lerobot.configs.train import TrainPipelineConfig

    for memory in ("action_12", "no_0"):
        name = f"oft_decision_{memory}_ws_grounded_block_readings_tuned"
        decision = json.loads((CONFIGS / "small" / f"{name}.json").read_text())
        first = json.loads((CONFIGS / "small" / f"{name}_think_first.json").read_text())
        assert {k for k in decision if decision[k] != first[k]} == {"policy", "job_name"}
        assert differing_policy_keys(first, decision) == {"think_first"}
        assert first["job_name"] == f"small_{name}_think_first"
        cfg = TrainPipelineConfig.from_pretrained(CONFIGS / "small" / f"{name}_think_first.json").policy
        assert cfg.think_first and cfg.think == "decision"


def test_the_layout_pair_is_the_think_first_pair_with_the_decision_levers():
    """``oft_decision_*_think_first_layout``: the think-first pair with the decision frames weighed five
    times over 24 frames, the pads listed and the decided place named in the span, the span's loss at
    the action loss's weight and a decoding budget that holds the longer span."""
    from lerobot.configs.train import TrainPipelineConfig

    levers = {"decision_weight", "decision_window", "decision_place", "decision_layout", "lm_loss_weight"}
    for memory in ("action_12", "no_0"):
        name = f"oft_decision_{memory}_ws_grounded_block_readings_tuned_think_first"
        first = json.loads((CONFIGS / "small" / f"{name}.json").read_text())
        laid = json.loads((CONFIGS / "small" / f"{name}_layout.json").read_text())
        assert {k for k in first if first[k] != laid[k]} == {"policy", "job_name"}
        assert differing_policy_keys(laid, first) == levers | {"subtask_max_tokens"}
        assert laid["job_name"] == f"small_{name}_layout"
        cfg = TrainPipelineConfig.from_pretrained(CONFIGS / "small" / f"{name}_layout.json").policy
        assert (cfg.decision_weight, cfg.decision_window, cfg.lm_loss_weight) == (5.0, 24, 1.0)
        assert cfg.decision_place and cfg.decision_layout and cfg.subtask_max_tokens == 48
    name = "oft_decision_{}_ws_grounded_block_readings_tuned_think_first_layout.json"
    pair = [json.loads((CONFIGS / "small" / name.format(m)).read_text()) for m in ("action_12", "no_0")]
    assert differing_policy_keys(*pair) == MEMORY_KEYS | {"memory_vision"}  # the memory alone


def test_the_wms_preset_is_the_wos_chunk_12_one_with_state_tokens_on_its_memory_frames():
    """``_wms_``: the wos chunk-12 preset with the memory frames' state tokens back and none on the
    current frame (``state_frames=memory``); without a memory that is no state at all, so its
    memory-free partner is the wos one."""
    from lerobot.configs.train import TrainPipelineConfig

    name = "oft_subtask_{}_grounded_count_left_objects_tuned.json"
    wms = json.loads((CONFIGS / "small" / name.format("action_12_wms")).read_text())
    wos = json.loads((CONFIGS / "small" / name.format("action_12_wos")).read_text())
    assert {k for k in wms if wms[k] != wos[k]} == {"policy", "job_name"}
    assert differing_policy_keys(wms, wos) == {"use_state", "state_frames"}
    cfg = TrainPipelineConfig.from_pretrained(CONFIGS / "small" / name.format("action_12_wms"))
    assert cfg.policy.use_state and cfg.policy.state_frames == "memory" and cfg.batch_size == 64
    free = json.loads((CONFIGS / "small" / name.format("no_0_wos")).read_text())
    assert differing_policy_keys(wms, free) == MEMORY_KEYS | {"memory_vision", "use_state", "state_frames"}


@pytest.mark.parametrize(
    ("name", "tower"), [("bell_jitter_frozen", "bell_jitter"), ("bell_randconv_frozen", "bell_randconv")]
)
def test_the_augmented_frozen_bell_pairs_read_a_tower_grounded_with_their_augmentation(name, tower):
    """The _bell_jitter_frozen and _bell_randconv_frozen pairs: the grounded bell pair with act_cpu_jitter's
    augmentation (the _bell_jitter preset's), read through a tower grounded with colour jitter
    (``activearena-ground-vision --jitter``; ``--random-conv`` too for the second) and kept frozen (the
    chunk-12 one's memory from that tower's table), at the frozen count runs' lr 3e-4 and 2,000 steps;
    the two of a pair still differ only in the memory, and LeRobot parses both."""
    from lerobot.configs.train import TrainPipelineConfig

    pair = {}
    for memory in ("action_12", "no_0"):
        frozen = pair[memory] = small_preset(memory, name)
        grounded = small_preset(memory, "bell")
        assert frozen["dataset"] == small_preset("action_12", "bell_jitter")["dataset"]
        assert {k for k in frozen if frozen[k] != grounded[k]} == {"dataset", "policy", "steps", "job_name"}
        assert differing_policy_keys(frozen, grounded) == {
            "vlm_path",
            "freeze_vision",
            "optimizer_lr",
            "head_lr",
            "scheduler_warmup_steps",
            "scheduler_decay_steps",
        } | ({"vision_cache"} if memory == "action_12" else set())
        assert frozen["policy"]["vlm_path"] == f"outputs/small_vlm_v256d4_grounded_{tower}"
        assert frozen["steps"] == frozen["policy"]["scheduler_decay_steps"] == 2000
        cfg = TrainPipelineConfig.from_pretrained(
            CONFIGS / "small" / f"oft_subtask_{memory}_ws_grounded_{name}.json"
        )
        assert cfg.policy.freeze_vision and cfg.dataset.image_transforms.enable
    chunk, free = pair["action_12"], pair["no_0"]
    assert differing_policy_keys(chunk, free) == MEMORY_KEYS
    assert {k for k in chunk if chunk[k] != free[k]} == {"policy", "job_name"}
    assert chunk["policy"]["vision_cache"].endswith(f"_grounded_{tower.removeprefix('bell_')}.safetensors")


def test_the_inspection_pair_is_the_layout_pair_with_every_later_stage_setting_in_one_run():
    """``oft_decision_*_ws_inspection``: the layout pair with the settings its chain of fine-tuning
    stages added one at a time (the decision clause weighed 10, the place spelled out, the first 32
    frames weighed 4) from the first step, for one 8,000-step run on the inspection recipe's build;
    the two still differ only in the memory, and LeRobot parses both."""
    from lerobot.configs.train import TrainPipelineConfig

    from lerobot_activearena.datasets_build.recipe import load_recipe

    stages = {"decision_token_weight", "decision_where", "opening_weight", "opening_window"}
    pair = {}
    for memory in ("action_12", "no_0"):
        laid = json.loads(
            (
                CONFIGS
                / "small"
                / f"oft_decision_{memory}_ws_grounded_block_readings_tuned_think_first_layout.json"
            ).read_text()
        )
        one = pair[memory] = json.loads(
            (CONFIGS / "small" / f"oft_decision_{memory}_ws_inspection.json").read_text()
        )
        paths = {"vlm_path"} | ({"vision_cache"} if memory == "action_12" else set())
        schedule = {"subtask_max_tokens", "scheduler_decay_steps"}
        assert differing_policy_keys(one, laid) == stages | paths | schedule
        assert one["dataset"] == {**laid["dataset"], "repo_id": "local/cpu_inspection"}
        assert one["steps"] == one["policy"]["scheduler_decay_steps"] == 8000
        cfg = TrainPipelineConfig.from_pretrained(
            CONFIGS / "small" / f"oft_decision_{memory}_ws_inspection.json"
        )
        p = cfg.policy
        assert (p.decision_token_weight, p.opening_weight, p.opening_window) == (10.0, 4.0, 32)
        assert p.decision_where and p.decision_layout and p.think_first and p.subtask_max_tokens == 64
    assert differing_policy_keys(pair["action_12"], pair["no_0"]) == MEMORY_KEYS | {"memory_vision"}
    recipe = load_recipe(CONFIGS.parents[1] / "datasets_build" / "cpu_inspection.json")
    assert (recipe["tasks"], recipe["episodes"], recipe["image_size"]) == (
        "check_block_color",
        900,
        "192x256",
    )
    assert (recipe["reading_variants"], recipe["decision_period"], recipe["turn_error_subtask"]) == (3, 16, 4)
