"""Processors of every ActiveArena-VLA head. Pre: rename -> batch -> annotations (training only: subtask
text, keyframe memory) -> VLM inputs (Qwen image processing and tokenisation) -> normalise state /
action -> device. Post: unnormalise the action -> CPU. Saved with the checkpoint, so
``lerobot-eval --policy.path=...`` rebuilds them with no extra flags."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import torch
from lerobot.configs.types import PipelineFeatureType, PolicyFeature
from lerobot.lerobot_types import TransitionKey
from lerobot.processor import (
    PolicyAction,
    PolicyActionProcessorStep,
    PolicyProcessorPipeline,
    ProcessorStep,
    ProcessorStepRegistry,
)
from lerobot.processor.factory import make_default_policy_processor_steps, make_policy_processor_pipelines
from lerobot.utils.constants import OBS_STATE

from ...sim.action import HEAD_PITCH, TORSO_YAW
from ...sim.embodiment import HOME_HEAD_PITCH, HOME_TORSO_YAW
from ...sim.scene import HEAD_HEIGHT, HEAD_WIDTH
from .configuration_activearena_vla import IMAGE_KEY, ActiveArenaVLAConfig
from .helpers import pack_frames
from .vlm_loading import load_from_vlm_path

VLM = "observation.vlm."
# PIXELS holds the present frames only, packed in (sample, frame) order: (frames present, patches, dim)
# where every frame has one size, else (all their patches, dim) (--policy.current_image_pixels);
# FRAME_VALID (batch, frames) says which they are, GRID (batch, frames, 3) gives every slot's grid.
PIXELS, GRID, FRAME_VALID = VLM + "pixel_values", VLM + "image_grid_thw", VLM + "frame_valid"
PREFIX_IDS, PROMPT_IDS, PROMPT_MASK = VLM + "prefix_ids", VLM + "prompt_ids", VLM + "prompt_mask"
THINK_IDS, THINK_MASK, RAW_STATE = VLM + "think_ids", VLM + "think_mask", VLM + "raw_state"
# training with a vision cache: (batch, history) global indices of the memory frames, -1 where padded
MEMORY_INDEX = VLM + "memory_index"
# evaluation with --policy.current_image_pixels: (pixels, grids) of the env frames at the memory's size
MEMORY_PIXELS = VLM + "memory_pixels"
# training with --policy.decision_weight: (batch,) each sample's action-loss weight
ACTION_WEIGHT = VLM + "action_weight"
FRAMES = VLM + "frames"  # an env step's current frames (EnvFrames), until the policy needs their pixels
PREFIX = "<|im_start|>user\n"
ASSISTANT = "<|im_end|>\n<|im_start|>assistant\n"  # closes a user turn, opens the answer
PROMPT = (
    "The images are ordered from earliest to latest, and the last image is the current view. "
    "Task: {instruction}<|im_end|>\n<|im_start|>assistant\n"
)
THINK = "<think>{target}</think><|im_end|>"
KEYFRAME_MEMORIES = ("subtask", "motion", "planned")  # memories the annotation step loads per sample


def _pad_flag(comp: dict, batch_size: int, n_frames: int) -> torch.Tensor:
    pad = comp.get(f"{IMAGE_KEY}_is_pad")
    if pad is None or tuple(pad.shape) != (batch_size, n_frames):
        return torch.zeros(batch_size, n_frames, dtype=torch.bool)
    return pad.bool().cpu()


@dataclass(frozen=True)
class EnvFrames:
    """An env step's current (B, C, H, W) float frames, left where LeRobot made them (the CPU): not a
    tensor, so the device step does not copy them to the GPU at the steps that never read them."""

    images: torch.Tensor


def to_uint8(images: torch.Tensor) -> torch.Tensor:
    """LeRobot's float images in [0, 1] as the uint8 the image processor reads."""
    return (images.float().clamp(0, 1) * 255).round().to(torch.uint8)


def one_token_pixels(image_processor) -> int:
    """The pixels of one merged visual token: the smallest image the backbone reads."""
    return (image_processor.patch_size * image_processor.merge_size) ** 2


def image_inputs(
    image_processor, frames: torch.Tensor, max_pixels: int, min_pixels: int, device: torch.device
) -> tuple[torch.Tensor, torch.Tensor]:
    """Qwen's image processing of (N, C, H, W) uint8 frames: the (N, patches, dim) pixel values and the
    (N, 3) grids (on the CPU)."""
    out = image_processor(
        images=list(frames.to(device)),
        return_tensors="pt",
        device=device,
        max_pixels=max_pixels,
        min_pixels=min_pixels,
    )
    pv = out["pixel_values"]
    return pv.reshape(len(frames), -1, pv.shape[-1]), out["image_grid_thw"].cpu()


def pixel_budgets(
    image_max_pixels: int, current_image_pixels: int | None, min_pixels: int
) -> tuple[tuple[int, int], tuple[int, int]]:
    """The (max, min) pixels the memory frames and the current frame are read at: the current one at
    exactly ``current_image_pixels`` where set (upscaled where the image is smaller), else as the memory's."""
    memory = (image_max_pixels, min_pixels)
    return memory, memory if current_image_pixels is None else (current_image_pixels, current_image_pixels)


def frame_inputs(
    image_processor, frames: torch.Tensor, config, device: torch.device, memory: bool = False
) -> tuple[torch.Tensor, torch.Tensor]:
    """``image_inputs`` of env frames as the policy ``config`` reads its current frame (``memory``: as
    it keeps them in its memory)."""
    budgets = pixel_budgets(
        config.image_max_pixels, config.current_image_pixels, one_token_pixels(image_processor)
    )
    return image_inputs(image_processor, frames, *budgets[0 if memory else 1], device)


def frame_grid(image_processor, height: int, width: int, max_pixels: int, min_pixels: int) -> torch.Tensor:
    """The (3,) grid ``image_inputs`` gives a ``height`` x ``width`` image (Qwen's smart resize)."""
    from transformers.models.qwen2_vl.image_processing_qwen2_vl import smart_resize

    patch = image_processor.patch_size
    h, w = smart_resize(height, width, patch * image_processor.merge_size, min_pixels, max_pixels)
    return torch.tensor([1, h // patch, w // patch])


# what the annotation step writes into training batches, set from the policy config when it is built
ANNOTATION_SETTINGS = (
    "memory",
    "history",
    "think",
    "decision_weight",
    "decision_window",
    "opening_weight",
    "opening_window",
    "miss_weight",
    "decision_place",
    "decision_layout",
    "decision_where",
)
# what the inputs step reads from the policy config: checked alike
INPUT_SETTINGS = ("current_image_pixels",)


def check_saved_annotations(config, checkpoint) -> None:
    """Refuse a policy config whose annotation settings differ from those its checkpoint's saved
    preprocessor will apply: lerobot-train fine-tuning (``--policy.pretrained_path``) loads that
    preprocessor as saved, so the command line's settings would silently not reach the batches."""
    import json
    from pathlib import Path

    path = Path(checkpoint) / "policy_preprocessor.json"
    if not path.is_file():
        return  # a hub id or a bare model folder: nothing saved to disagree with
    steps = json.loads(path.read_text()).get("steps", [])
    differ = []
    for suffix, step_type, names in (
        ("_annotations", ActiveArenaAnnotationStep, ANNOTATION_SETTINGS),
        ("_vlm_inputs", ActiveArenaVLMInputsStep, INPUT_SETTINGS),
    ):
        fields = step_type.__dataclass_fields__  # a setting saved before it existed: its default
        for st in steps:
            if not str(st.get("registry_name", "")).endswith(suffix):
                continue
            for name in names:
                asked, kept = getattr(config, name), st.get("config", {}).get(name, fields[name].default)
                if asked != kept:
                    differ.append(f"{name}={asked!r} (saved: {kept!r})")
    if differ:
        raise ValueError(
            f"the policy config asks for {', '.join(differ)}, but {path} prepares training batches as "
            "saved and lerobot-train loads it unchanged: set these in its step's config (or copy the "
            "checkpoint and edit the copy's), or leave them off the command line"
        )


# registry names keep their first (OFT) spelling: saved checkpoints refer to them
@ProcessorStepRegistry.register(name="activearena_oft_annotations")
@dataclass
class ActiveArenaAnnotationStep(ProcessorStep):
    """Training only (batches that carry the dataset ``index``): adds the annotated current subtask
    text and, for the subtask / motion / planned write policies, the keyframe-memory frames and states."""

    dataset_root: str | None = None
    repo_id: str = "local/activearena"
    memory: str = "chunk"
    history: int = 12
    think: str = "none"
    subtask_prompt: bool = False  # the prompt names the current subtask (ActiveArena-Plan's executor)
    # the chunk memory's frames come as indices into a vision cache (their states from the dataset)
    cached_memory: bool = False
    # the action-loss weight of the frames where the expert starts acting on a reading (1: none)
    decision_weight: float = 1.0
    decision_window: int = 16
    # the action-loss weight of every episode's first frames (1: none)
    opening_weight: float = 1.0
    opening_window: int = 32
    # the action-loss weight of a grasp-retry build's missed tries (1: none)
    miss_weight: float = 1.0
    decision_place: bool = False  # think=decision: the decided object's place named too
    decision_layout: bool = False  # ... after the places of all of its kind
    decision_where: bool = False  # ... and where the object acted on lies (cm, deg from the base)
    _ann: Any = field(default=None, init=False, repr=False)
    _onsets: Any = field(default=None, init=False, repr=False)
    _misses: Any = field(default=None, init=False, repr=False)

    def _needs_subtask(self) -> bool:
        return self.think == "subtask" or self.subtask_prompt

    def _cached_chunk(self) -> bool:
        return self.cached_memory and self.memory == "chunk" and self.history > 0

    def _needed(self) -> bool:
        return (
            self._needs_subtask()
            or self.think == "decision"
            or (self.memory in KEYFRAME_MEMORIES and self.history > 0)
            or self._cached_chunk()
            or self._weighted()
        )

    def _weighted(self) -> bool:
        return self.decision_weight != 1 or self.opening_weight != 1 or self.miss_weight != 1

    def __call__(self, transition):
        comp = transition.get(TransitionKey.COMPLEMENTARY_DATA) or {}
        index = comp.get("index")
        if index is None or not self._needed():
            return transition  # evaluation: the policy's own memory bank supplies history
        if self.dataset_root is None:
            raise ValueError(
                "this ActiveArena-VLA configuration reads the dataset's annotations at training time; "
                "set --policy.dataset_root (lerobot-train fills it from --dataset.root)"
            )
        if self._ann is None:
            from .dataset_annotations import DatasetAnnotations

            self._ann = DatasetAnnotations(self.dataset_root, self.repo_id)
        idx = torch.as_tensor(index).reshape(-1).tolist()
        self._check_frames(idx, comp.get("episode_index"))
        comp = dict(comp)
        if self._needs_subtask():
            comp["subtask"] = [self._ann.subtask(i) for i in idx]
        if self.think == "decision":
            comp["think_target"] = [
                self._ann.subtask_and_decision(
                    i, self.decision_place, self.decision_layout, self.decision_where
                )
                for i in idx
            ]
        obs = dict(transition[TransitionKey.OBSERVATION])
        if self.memory in KEYFRAME_MEMORIES and self.history > 0:
            img = obs[IMAGE_KEY]
            if img.dim() != 4:
                raise ValueError(f"keyframe memory expects the current frame only, got {tuple(img.shape)}")
            obs[IMAGE_KEY], states, comp[f"{IMAGE_KEY}_is_pad"] = self._ann.memory_batch(
                torch.tensor(idx), img, obs.get(OBS_STATE), self.memory, self.history
            )
            if states is not None:
                obs[OBS_STATE] = states
        if self._weighted():
            comp[ACTION_WEIGHT] = self._action_weights(idx)
        if self._cached_chunk():
            comp[MEMORY_INDEX], states = self._ann.memory_index_batch(
                torch.tensor(idx), obs.get(OBS_STATE), self.history
            )
            if states is not None:
                obs[OBS_STATE] = states
        out = dict(transition)
        out[TransitionKey.OBSERVATION], out[TransitionKey.COMPLEMENTARY_DATA] = obs, comp
        return out

    def _check_frames(self, idx: list[int], episodes) -> None:
        """The batch's frames must be the annotated dataset's (its ``episode_index`` at each ``index``):
        fine-tuning on another build loads the checkpoint's saved step, which reads the build that
        checkpoint was trained on."""
        ours = self._ann.cols["episode_index"]
        theirs = None if episodes is None else torch.as_tensor(episodes).reshape(-1).tolist()
        if max(idx) < len(ours) and (
            theirs is None or all(ours[i] == e for i, e in zip(idx, theirs, strict=True))
        ):
            return
        raise ValueError(
            f"the training frames are not those of {self.dataset_root}, whose annotations this step reads: "
            "a checkpoint fine-tuned on another build (--policy.pretrained_path) keeps the annotation step "
            "it was saved with; copy the checkpoint and set dataset_root and repo_id in its "
            "policy_preprocessor.json's annotation step to the training dataset's (--dataset.root, "
            "--dataset.repo_id)"
        )

    def _action_weights(self, idx: list[int]) -> torch.Tensor:
        weight = torch.ones(len(idx))
        if self.opening_weight != 1:
            opening = torch.as_tensor(self._ann.cols["frame_index"][idx] < self.opening_window)
            weight = torch.where(opening, self.opening_weight, weight)
        if self.miss_weight != 1:
            if self._misses is None:
                self._misses = self._ann.miss_frames()
                if not self._misses.any():
                    raise ValueError(
                        f"--policy.miss_weight={self.miss_weight} weighs a grasp-retry build's missed tries, and "
                        f"{self.dataset_root} holds none (no expert_notes.grasp_misses): train a build made "
                        "with --grasp-miss, or leave miss_weight at 1"
                    )
            weight = torch.where(torch.as_tensor(self._misses[idx]), self.miss_weight * weight, weight)
        if self.decision_weight == 1:
            return weight
        if self._onsets is None:
            self._onsets = self._ann.decision_onsets(self.decision_window)
            if not self._onsets.any():
                raise ValueError(
                    f"--policy.decision_weight={self.decision_weight} weights the frames where the expert "
                    f"acts on a reading, and {self.dataset_root} holds none (no expert_notes.inspections): "
                    "train an inspection task's build, or leave decision_weight at 1"
                )
        onset = torch.as_tensor(self._onsets[idx])
        return torch.where(onset, self.decision_weight * weight, weight).float()

    def get_config(self) -> dict[str, Any]:
        return {
            "decision_weight": self.decision_weight,
            "decision_window": self.decision_window,
            "opening_weight": self.opening_weight,
            "opening_window": self.opening_window,
            "miss_weight": self.miss_weight,
            "decision_place": self.decision_place,
            "decision_layout": self.decision_layout,
            "decision_where": self.decision_where,
            "dataset_root": self.dataset_root,
            "repo_id": self.repo_id,
            "memory": self.memory,
            "history": self.history,
            "think": self.think,
            "subtask_prompt": self.subtask_prompt,
            "cached_memory": self.cached_memory,
        }

    def transform_features(self, features: dict[PipelineFeatureType, dict[str, PolicyFeature]]):
        return features


@ProcessorStepRegistry.register(name="activearena_oft_vlm_inputs")
@dataclass
class ActiveArenaVLMInputsStep(ProcessorStep):
    """Qwen3-VL inputs: every head image (history + current) through the model's image processor,
    the instruction prompt and (training) the ``<think>`` target through its tokenizer. The policy
    assembles the token sequence, so its memory bank can reuse processed frames at evaluation."""

    vlm_path: str = "Qwen/Qwen3-VL-2B-Instruct"
    think: str = "none"
    think_template: str = THINK  # the training target's text around the think target
    prompt_template: str = PROMPT  # the prompt after the images; {instruction}: the task (or subtask)
    subtask_prompt: bool = False  # training: the prompt names the annotated subtask, not the task
    image_max_pixels: int = HEAD_WIDTH * HEAD_HEIGHT
    current_image_pixels: int | None = None  # the current frame's size (config's); None: as the memory's
    # Where the image processor runs: the policy's device, so on a GPU the resizing and patching of
    # the 13 frames per sample happen there and do not hold up the training loop's CPU.
    device: str = "cpu"
    # evaluation: an env step's frames reach the policy as uint8 (FRAMES) and become pixels only where
    # the policy reads them; False processes every step's frames here (the same actions, slower)
    defer_env_frames: bool = True
    _processor: Any = field(default=None, init=False, repr=False)
    _min_pixels: int = field(default=0, init=False, repr=False)
    _tokenized: dict = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self):
        from transformers import AutoProcessor

        self._processor = load_from_vlm_path(AutoProcessor.from_pretrained, self.vlm_path, "processor")
        images = self._processor.image_processor
        self._min_pixels = one_token_pixels(images)
        if self.image_max_pixels < self._min_pixels:
            raise ValueError(
                f"image_max_pixels={self.image_max_pixels} is below one token of {self.vlm_path!r} "
                f"({self._min_pixels} pixels); raise --policy.image_max_pixels"
            )
        if self.current_image_pixels is not None and self.current_image_pixels < self._min_pixels:
            raise ValueError(
                f"current_image_pixels={self.current_image_pixels} is below one token of {self.vlm_path!r} "
                f"({self._min_pixels} pixels); raise --policy.current_image_pixels"
            )

    @property
    def processor(self):
        """The backbone's Hugging Face processor (tokenizer and image processor) this step uses."""
        return self._processor

    def _tokenize(self, texts: list[str]) -> tuple[torch.Tensor, torch.Tensor]:
        # an evaluation batch repeats the same instructions every env step: tokenised once
        key = tuple(texts)
        if key not in self._tokenized:
            if len(self._tokenized) >= 256:
                self._tokenized.clear()
            tok = self._processor.tokenizer(
                texts, padding=True, padding_side="right", return_tensors="pt", add_special_tokens=False
            )
            self._tokenized[key] = tok["input_ids"], tok["attention_mask"].bool()
        ids, mask = self._tokenized[key]
        return ids.clone(), mask.clone()

    def __call__(self, transition):
        obs = dict(transition[TransitionKey.OBSERVATION])
        comp = dict(transition.get(TransitionKey.COMPLEMENTARY_DATA) or {})
        if IMAGE_KEY not in obs:
            raise KeyError(
                f"ActiveArena-VLA policies need {IMAGE_KEY!r} in the observation (got {sorted(obs)})"
            )
        img = obs.pop(IMAGE_KEY)
        img = img[:, None] if img.dim() == 4 else img
        batch_size, n_frames = img.shape[:2]
        valid = ~_pad_flag(comp, batch_size, n_frames)
        memory_index = comp.pop(MEMORY_INDEX, None)
        if memory_index is not None:  # the memory frames' features come from a vision cache by index
            if n_frames != 1:
                raise ValueError(
                    f"a vision-cached memory reads the current frame only from the dataset, got {n_frames} "
                    "frames a sample: the policy's observation_delta_indices must be None"
                )
            obs[MEMORY_INDEX] = memory_index
        # Padded history frames (before the episode start) are never read: only present frames go
        # through the image processor, and only theirs are kept.
        device = self._device()
        if self.defer_env_frames and n_frames == 1 and transition.get(TransitionKey.ACTION) is None:
            # an env step: the policy turns the frames into pixels only at the steps that read them
            # (chunk boundaries and memory writes), 1 step in 16 with the chunk memory; the others
            # neither copy them to the device nor convert them
            obs[FRAMES] = EnvFrames(img[:, 0].detach())
        else:
            obs[PIXELS], obs[GRID] = self._pixels(img, valid, device)
        if memory_index is not None:  # history slots first, at the memory's (the cache's) size
            memory_grid = frame_grid(self._processor.image_processor, *img.shape[-2:], *self.budgets[0])
            obs[GRID] = torch.cat(
                [memory_grid.repeat(batch_size, memory_index.shape[1], 1), obs[GRID]], dim=1
            )
            valid = torch.cat([memory_index >= 0, valid], dim=1)
        obs[FRAME_VALID] = valid
        if OBS_STATE in obs:
            obs[RAW_STATE] = obs[OBS_STATE].clone()
        tasks = comp.get("task")
        if tasks is None:
            raise ValueError("ActiveArena-VLA policies need the task instruction ('task') in the batch")
        tasks = [tasks] * batch_size if isinstance(tasks, str) else list(tasks)
        obs[PREFIX_IDS] = self._tokenize([PREFIX] * batch_size)[0]
        named = list(comp["subtask"]) if self.subtask_prompt and "subtask" in comp else tasks
        obs[PROMPT_IDS], obs[PROMPT_MASK] = self._tokenize(
            [self.prompt_template.format(instruction=t) for t in named]
        )
        if transition.get(TransitionKey.ACTION) is not None and self.think != "none":
            if "think_target" in comp:  # a complete target written by the annotation step
                targets = list(comp["think_target"])
            elif self.think in ("subtask", "decision"):
                if "subtask" not in comp:
                    raise ValueError(
                        f"think={self.think} needs the annotated subtask text: train on an ActiveArena "
                        "dataset (activearena-build-dataset) with --policy.dataset_root set"
                    )
                targets = list(comp["subtask"])
            else:
                targets = tasks
            obs[THINK_IDS], obs[THINK_MASK] = self._tokenize(
                [self.think_template.format(target=t) for t in targets]
            )
        out = dict(transition)
        out[TransitionKey.OBSERVATION], out[TransitionKey.COMPLEMENTARY_DATA] = obs, comp
        return out

    def _pixels(self, img: torch.Tensor, valid: torch.Tensor, device) -> tuple[torch.Tensor, torch.Tensor]:
        """PIXELS and GRID of (batch, frames, C, H, W) float images: the present frames', the last slot
        (the current frame) at ``current_image_pixels`` where set, the others at ``image_max_pixels``."""
        images = self._processor.image_processor
        memory_budget, current_budget = self.budgets
        current = torch.zeros_like(valid)
        current[:, -1] = True
        groups = [(~current, memory_budget), (current, current_budget)]
        if current_budget == memory_budget:  # one size: the frames through one call
            groups = [(torch.ones_like(valid), memory_budget)]
        grids = torch.zeros(*valid.shape, 3, dtype=torch.long)
        parts = []
        for where, (high, low) in groups:
            present = where & valid
            if not bool(present.any()):
                continue
            frames = to_uint8(img.detach().to(device)[present.to(device)])
            pv, grid = image_inputs(images, frames, high, low, device)
            grids[present] = grid
            parts.append((present.nonzero().tolist(), pv))
        # a padded slot (before the episode start) is never read: it gets its sample's current grid
        grids = torch.where(valid[..., None], grids, grids[:, -1:])
        if len(parts) == 1:  # already in (sample, slot) order
            return parts[0][1], grids
        rows = {tuple(key): p for keys, pv in parts for key, p in zip(keys, pv, strict=True)}
        return pack_frames([rows[k] for k in sorted(rows)]), grids

    @property
    def budgets(self) -> tuple[tuple[int, int], tuple[int, int]]:
        """The (max, min) pixels the memory frames and the current frame are read at (``pixel_budgets``)."""
        return pixel_budgets(self.image_max_pixels, self.current_image_pixels, self._min_pixels)

    def _device(self) -> torch.device:
        """The configured device, or the CPU where it does not exist (a CUDA checkpoint evaluated on a
        CPU machine with --policy.device=cpu)."""
        dev = torch.device(self.device)
        if dev.type == "cuda" and not torch.cuda.is_available():
            return torch.device("cpu")
        return dev

    def get_config(self) -> dict[str, Any]:
        return {
            "vlm_path": self.vlm_path,
            "think": self.think,
            "think_template": self.think_template,
            "prompt_template": self.prompt_template,
            "subtask_prompt": self.subtask_prompt,
            "image_max_pixels": self.image_max_pixels,
            "current_image_pixels": self.current_image_pixels,
            "device": self.device,
            "defer_env_frames": self.defer_env_frames,
        }

    def transform_features(self, features: dict[PipelineFeatureType, dict[str, PolicyFeature]]):
        return features


@ProcessorStepRegistry.register(name="activearena_hold_view_at_home")
@dataclass
class HoldViewAtHomeStep(PolicyActionProcessorStep):
    """ActiveArena-Fixed's output: the torso yaw and head pitch of every action are the home pose
    (the policy learns the arms and grippers only)."""

    def action(self, action: PolicyAction) -> PolicyAction:
        action = action.clone()
        action[..., TORSO_YAW] = HOME_TORSO_YAW
        action[..., HEAD_PITCH] = HOME_HEAD_PITCH
        return action

    def transform_features(self, features: dict[PipelineFeatureType, dict[str, PolicyFeature]]):
        return features


def make_activearena_vla_pre_post_processors(
    config: ActiveArenaVLAConfig,
    dataset_stats: dict[str, dict[str, torch.Tensor]] | None = None,
    dataset_meta: Any | None = None,
    think_template: str = THINK,
    after_normalize: tuple[ProcessorStep, ...] = (),
    prompt_template: str = PROMPT,
    subtask_prompt: bool = False,
    annotation_step: type[ActiveArenaAnnotationStep] | None = None,
) -> tuple[
    PolicyProcessorPipeline[dict[str, Any], dict[str, Any]],
    PolicyProcessorPipeline[PolicyAction, PolicyAction],
]:
    """The shared pipelines; a head passes its own think and prompt templates, annotation step and
    steps that run after normalisation."""
    # lerobot-train hands the dataset metadata to make_policy, which keeps it on the config
    dataset_meta = dataset_meta or getattr(config, "_runtime_dataset_meta", None)
    if dataset_meta is not None and getattr(dataset_meta, "root", None) is not None:
        config.dataset_root = str(dataset_meta.root)
    s = make_default_policy_processor_steps(config, dataset_stats, normalizer_device=config.device)
    annotations = (annotation_step or ActiveArenaAnnotationStep)(
        dataset_root=config.dataset_root,
        repo_id=getattr(dataset_meta, "repo_id", None) or "local/activearena",
        memory=config.memory,
        history=config.history,
        think=config.think,
        subtask_prompt=subtask_prompt,
        cached_memory=bool(config.vision_cache),
        decision_weight=config.decision_weight,
        decision_window=config.decision_window,
        opening_weight=config.opening_weight,
        opening_window=config.opening_window,
        miss_weight=config.miss_weight,
        decision_place=config.decision_place,
        decision_layout=config.decision_layout,
        decision_where=config.decision_where,
    )
    inputs = ActiveArenaVLMInputsStep(
        vlm_path=config.vlm_path,
        think=config.think,
        think_template=think_template,
        prompt_template=prompt_template,
        subtask_prompt=subtask_prompt,
        image_max_pixels=config.image_max_pixels,
        current_image_pixels=config.current_image_pixels,
        device=config.device or "cpu",
    )
    return make_policy_processor_pipelines(
        input_steps=[
            s.rename_observations,
            s.add_batch_dim,
            annotations,
            inputs,
            s.normalize,
            *after_normalize,
            s.to_device,
        ],
        output_steps=[s.unnormalize, *([HoldViewAtHomeStep()] if config.fixed_view else []), s.to_cpu],
    )
