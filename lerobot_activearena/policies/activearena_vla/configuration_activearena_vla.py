"""The fields every ActiveArena-VLA head shares (paper App. "Internal Baseline Details"): the Qwen3-VL
backbone, up to K history images chosen by a memory write policy, optional per-image state tokens,
the ``<think>`` target, precision and the optimiser preset. Each head's registered config
(``activearena_oft``, ``activearena_groot``, ``activearena_fast``, ``activearena_planner``,
``activearena_plan``) subclasses it and adds its own fields."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from lerobot.configs.policies import PreTrainedConfig
from lerobot.configs.types import FeatureType, NormalizationMode
from lerobot.optim.optimizers import AdamWConfig
from lerobot.optim.schedulers import CosineDecayWithWarmupSchedulerConfig
from lerobot.utils.constants import ACTION, OBS_STATE

from ...annotations.keyframes import STRIDE, WRITE_POLICIES
from ...sim.action import ACTION_DIM, HEAD_PITCH, TORSO_YAW
from ...sim.scene import HEAD_HEIGHT, HEAD_WIDTH

IMAGE_KEY = "observation.images.head"
THINK_TARGETS = ("none", "instruction", "subtask", "decision")
MEMORY_ABLATIONS = ("none", "blank", "drop")
MEMORY_VISION = ("shared", "frozen")
DTYPES = ("auto", "float32", "bfloat16")
ATTENTION = ("sdpa", "flash_attention_2", "eager")
CHECKPOINT_LAYERS = ("all", "vision", "language")
CHECKPOINT_MODES = ("full", "selective")
RESIDUAL_DTYPES = ("float32", "compute")
COMPILE_LAYERS = ("none", "all", "vision", "language")
WEIGHT_DTYPES = ("float32", "bfloat16")
VIEW_DIMS = slice(TORSO_YAW, HEAD_PITCH + 1)  # the active-viewpoint dimensions: the action's last two


@dataclass
class ActiveArenaVLAConfig(PreTrainedConfig):
    # Backbone: a Hugging Face id or a local folder (model, tokenizer and image processor together).
    vlm_path: str = "Qwen/Qwen3-VL-2B-Instruct"
    # Memory: write policy for the history images and their number K (the current image is extra).
    memory: str = "chunk"
    history: int = 12
    use_state: bool = True
    # Which images get a state token: all | memory (the memory frames' poses only, none for the current
    # frame: the policy can recall where it saw a thing without copying where it is now).
    state_frames: str = "all"
    # Training: the chance that a sample's memory frames carry its current state in place of their own,
    # so their state tokens show no motion so far and the actions must place the reach from the images
    # (against copying the trend of the states); evaluation always reads the true states. 0: never.
    memory_state_dropout: float = 0.0
    # Training: the chance that a sample's memory frames are left out altogether, as at an episode's
    # first frame, so the chunk has to come from the current frame (against reading the motion from
    # what the memory shows); evaluation reads the whole memory. 0: never.
    memory_dropout: float = 0.0
    # Which tokens read the memory frames: all (every later token, as the paper's) | span (only the think
    # span: the prompt, the current frame and the action queries do not attend to a memory frame, so the
    # actions see the memory only through the span decoded from it).
    memory_readers: str = "all"
    # Keep the vision tower as it was loaded (no gradient, not optimised): a grounded tower as a fixed
    # feature extractor. With it, ``vision_cache`` (a table from activearena-cache-vision) gives the chunk
    # memory's history frames their features at training time by frame index: LeRobot then decodes only
    # the current frame and the tower reads only that (evaluation computes every frame live, the same).
    freeze_vision: bool = False
    vision_cache: str | None = None
    # Which tower reads the memory frames: shared (the policy's own, as the paper's) | frozen (a frozen
    # copy of the tower as loaded, while the policy's own tower trains on the current frame). With
    # frozen, a grounded tower's memory features stay fixed, so ``vision_cache`` serves them at training
    # time while the current frame's tower is fine-tuned (evaluation reads memory through the same copy).
    memory_vision: str = "shared"
    # The vision tower's learning rate when it trains (None: optimizer_lr, the backbone's).
    vision_lr: float | None = None
    # Evaluation-only ablation: "blank" replaces every memory image with a uniform gray one (the memory's
    # state tokens and frame slots stay), so a trained checkpoint can be scored without what it saw;
    # "drop" leaves the memory slots empty, as at an episode's first step (inputs seen in training).
    memory_ablation: str = "none"
    # ActiveArena-Fixed: learn only the 16 arm and gripper dimensions; every output chunk holds the
    # torso yaw and head pitch at home (evaluate with configs/env/activearena_fixed_*.json)
    fixed_view: bool = False
    # Auxiliary <think> target: none | instruction | subtask | decision (the subtask, followed from the
    # frame the expert read a hidden face on by the decision it took from it: "...; place on the red pad")
    think: str = "subtask"
    lm_loss_weight: float = 0.1
    # The action loss of the frames where the expert starts acting on what it read: the first
    # ``decision_window`` frames of every subtask that begins after a reading (expert_notes.inspections),
    # weighted ``decision_weight`` times the others (1: unweighted). Elsewhere the current view and
    # state show where the arm is heading; there only the memory (or the span it decoded) does.
    decision_weight: float = 1.0
    decision_window: int = 16
    # The action loss of every episode's first ``opening_window`` frames (the first turn towards the
    # object, decided from the home view, and on a ``--turn-error`` build the turn back), weighted
    # ``opening_weight`` times the others (1: unweighted); it multiplies decision_weight's.
    opening_weight: float = 1.0
    opening_window: int = 32
    # The action loss of a grasp-retry build's missed tries (``--grasp-miss``: the arm ran off the
    # recorded command, so those frames pair a state with a command it did not lead to), weighted
    # ``miss_weight`` times the others (0: left out; 1: unweighted); the retry after them counts fully.
    miss_weight: float = 1.0
    # think=decision: the decided object also named by its place among its kind by azimuth ("place on
    # the blue pad, the right one"), so the span carries where to go, not only what was read.
    decision_place: bool = False
    # with decision_place: the span first lists every object of that kind with its place ("blue pad right,
    # green pad middle, red pad left"), which the current view shows, so the decided place is a copy
    decision_layout: bool = False
    # think=decision: the span also says where the object to act on lies from the robot's base (the
    # episode's recorded placement, to a centimetre and a degree): while the inspected object is picked,
    # before any reading, "...; gray block at 40 cm, 54 deg"; after it, the decision ends "... at 36 cm,
    # 26 deg". The actions read that span, so the reach is spelled out before it is made.
    decision_where: bool = False
    # think=decision: the LM-loss weight of the decision clause's tokens (after the span's last ";": the
    # colour read and, with decision_place, the place) against the span's other tokens (1: a plain mean)
    decision_token_weight: float = 1.0
    subtask_max_tokens: int = 32  # greedy <think> decoding budget (OFT's memory=subtask, FAST's think span)
    chunk_size: int = 16
    # Actions run per predicted chunk. Chunk memory is written every 16th step (the paper's); below 16
    # it is written every gcd(16, n) steps so that every decision reads the frames 16, 32, ... steps
    # back, the history every training frame has.
    n_action_steps: int = 16
    state_hidden: int = 1024
    image_max_pixels: int = (
        HEAD_WIDTH * HEAD_HEIGHT
    )  # the head camera's native size: 192 visual tokens per image
    # The current frame's pixel budget, read at exactly this many pixels (upscaled where the image is
    # smaller: 196,608 reads a 192 x 256 frame at 384 x 512, 4x the tokens); the memory frames keep
    # image_max_pixels (and a vision cache made at it). None: the current frame as the memory's.
    current_image_pixels: int | None = None
    # Where the dataset's annotations are read at training time (subtask text, keyframe columns);
    # filled by lerobot-train from the dataset, unused at evaluation.
    dataset_root: str | None = None
    gradient_checkpointing: bool = False
    # The blocks that recompute their activations in the backward pass when gradient_checkpointing is
    # on: all | vision (the vision tower's: it holds most activations, 4 patches per merged token of 13
    # images a sample) | language (the language model's decoder layers)
    gradient_checkpointing_layers: str = "all"
    # With layers all or language: how many of the language model's decoder layers recompute, the first
    # N (the others keep their activations); None: every one. Between vision (fast, the most memory)
    # and all (the least): each checkpointed decoder layer trades its kept activations for a recompute.
    gradient_checkpointing_language_layers: int | None = None
    # What those blocks recompute: full (everything but their input: the least memory) | selective
    # (they keep their matrix multiplies' and attention's outputs and recompute only norms, activations,
    # rotary embeddings and casts: most of full's saving at a small part of its recompute time).
    gradient_checkpointing_mode: str = "full"
    # Run the language model once per sample over its own tokens instead of once over the batch padded
    # to its longest sample (training and uncached decoding): the same outputs without computing or
    # keeping the pads, which are a fifth to a half of the positions when the samples' memories differ.
    unpad_language_model: bool = False
    # Compute precision: auto (bfloat16 autocast on CUDA, float32 elsewhere) | float32 | bfloat16. The
    # parameters stay float32 (master weights: AdamW's small updates are kept, as DeepSpeed ZeRO-2 does
    # in the paper's run) unless weights_dtype=bfloat16, which halves their memory but rounds most
    # updates at lr 1e-5 away (warned).
    dtype: str = "auto"
    weights_dtype: str = "float32"
    # The backbone's residual streams under bfloat16 compute: float32 (the embeddings' dtype: every
    # addition, norm input and kept block input in float32) | compute (bfloat16, as the paper's
    # bfloat16 training has them; half their memory and traffic).
    residual_dtype: str = "float32"
    # torch.compile each of these blocks (none | all | vision | language): regional compilation, one
    # graph a block kind with dynamic shapes, fusing the element-wise work (norms, casts, rotary,
    # activations) between the matrix multiplies. The first steps compile (tens of seconds).
    compile_layers: str = "none"
    # The backbone's attention kernel: sdpa (PyTorch's fused scaled-dot-product attention: flash or
    # memory-efficient kernels on CUDA) | flash_attention_2 (needs the flash-attn package) | eager.
    attn_implementation: str = "sdpa"
    push_to_hub: bool = (
        False  # LeRobot's default (True) needs a repo id; opt in with --policy.push_to_hub=true
    )
    # Optimiser (paper: AdamW (0.9, 0.95), eps 1e-8, wd 1e-8, backbone 1e-5, heads 1e-4,
    # 5k-step linear warm-up, cosine to 5e-7, clip 1.0).
    optimizer_lr: float = 1e-5
    head_lr: float = 1e-4
    optimizer_betas: tuple[float, float] = (0.9, 0.95)
    optimizer_eps: float = 1e-8
    optimizer_weight_decay: float = 1e-8
    optimizer_grad_clip_norm: float = 1.0
    scheduler_warmup_steps: int = 5_000
    scheduler_decay_steps: int = 150_000
    scheduler_decay_lr: float = 5e-7
    normalization_mapping: dict[str, NormalizationMode] = field(
        default_factory=lambda: {
            "VISUAL": NormalizationMode.IDENTITY,
            "STATE": NormalizationMode.MEAN_STD,
            "ACTION": NormalizationMode.MEAN_STD,
        }
    )

    # a head whose memory is filled by a planner (memory=planned) sets this
    uses_planner_memory = False
    # a head that decodes its own subtask at evaluation to decide memory writes (memory=subtask) sets this
    supports_subtask_memory = False

    def __post_init__(self):
        super().__post_init__()
        if self.memory not in WRITE_POLICIES:
            raise ValueError(f"--policy.memory must be one of {WRITE_POLICIES}, got {self.memory!r}")
        if self.memory == "planned" and not self.uses_planner_memory:
            raise ValueError(
                "memory=planned is ActiveArena-Plan's executor memory (frames its planner retrieves): "
                "use --policy.type=activearena_plan"
            )
        if self.memory == "subtask" and not self.supports_subtask_memory:
            raise ValueError(
                "memory=subtask writes a frame where the policy's own decoded subtask changes, which "
                "ActiveArena-VLA-OFT implements (the paper's ablation): use --policy.type=activearena_oft"
            )
        if self.think not in THINK_TARGETS:
            raise ValueError(f"--policy.think must be one of {THINK_TARGETS}, got {self.think!r}")
        for name, allowed in (
            ("dtype", DTYPES),
            ("weights_dtype", WEIGHT_DTYPES),
            ("attn_implementation", ATTENTION),
            ("memory_ablation", MEMORY_ABLATIONS),
            ("memory_vision", MEMORY_VISION),
            ("gradient_checkpointing_layers", CHECKPOINT_LAYERS),
            ("gradient_checkpointing_mode", CHECKPOINT_MODES),
            ("residual_dtype", RESIDUAL_DTYPES),
            ("compile_layers", COMPILE_LAYERS),
        ):
            if getattr(self, name) not in allowed:
                raise ValueError(f"--policy.{name} must be one of {allowed}, got {getattr(self, name)!r}")
        n_language = self.gradient_checkpointing_language_layers
        if n_language is not None and (n_language < 0 or self.gradient_checkpointing_layers == "vision"):
            raise ValueError(
                "--policy.gradient_checkpointing_language_layers counts the language model's decoder layers "
                "that recompute: a number >= 0 with gradient_checkpointing_layers=all or language (with "
                f"vision no language layer recomputes), got {n_language} with "
                f"gradient_checkpointing_layers={self.gradient_checkpointing_layers}"
            )
        if (
            self.compile_layers != "none"
            and self.gradient_checkpointing
            and (self.gradient_checkpointing_mode == "selective")
        ):
            raise ValueError(
                "--policy.compile_layers does not combine with gradient_checkpointing_mode=selective "
                "(PyTorch's selective checkpointing cannot see inside compiled blocks): use "
                "gradient_checkpointing_mode=full, or compile_layers=none"
            )
        if self.history < 0:
            raise ValueError(f"--policy.history must be >= 0, got {self.history}")
        if self.memory == "none":
            self.history = 0
        if self.memory_ablation != "none" and (self.history == 0 or self.uses_planner_memory):
            raise ValueError(
                f"--policy.memory_ablation={self.memory_ablation} blanks or drops the frames of a chunk, motion or "
                f"subtask memory; this policy has {'a planner' if self.uses_planner_memory else 'no'} memory"
            )
        if not 1 <= self.n_action_steps <= self.chunk_size:
            raise ValueError(
                f"n_action_steps ({self.n_action_steps}) must be in 1..chunk_size ({self.chunk_size})"
            )
        if not 0.0 <= self.memory_state_dropout <= 1.0:
            raise ValueError(
                f"--policy.memory_state_dropout is a probability in [0, 1], got {self.memory_state_dropout}"
            )
        if self.memory_state_dropout and not (self.use_state and self.uses_history):
            raise ValueError(
                "--policy.memory_state_dropout replaces the memory frames' states: it needs use_state=true and "
                f"a memory (got use_state={self.use_state}, memory={self.memory}, history={self.history})"
            )
        if not 0.0 <= self.memory_dropout <= 1.0:
            raise ValueError(f"--policy.memory_dropout is a probability in [0, 1], got {self.memory_dropout}")
        if self.memory_dropout and not self.uses_history:
            raise ValueError(
                "--policy.memory_dropout leaves a sample's memory frames out: it needs a memory "
                f"(got memory={self.memory}, history={self.history})"
            )
        if self.memory_readers not in ("all", "span"):
            raise ValueError(f"--policy.memory_readers must be all or span, got {self.memory_readers!r}")
        if self.memory_readers == "span" and (self.think == "none" or not self.uses_history):
            raise ValueError(
                "--policy.memory_readers=span lets only the think span read the memory frames: it needs a "
                f"think target and a memory (got think={self.think}, memory={self.memory}, history={self.history})"
            )
        if self.memory_readers == "span" and not getattr(self, "think_first", False):
            raise ValueError(
                "--policy.memory_readers=span: the actions must read the span that reads the memory, which "
                "only activearena_oft with the span before its action queries does; add "
                "--policy.think_first=true (activearena_oft)"
            )
        if self.memory_readers == "span" and self.attn_implementation == "flash_attention_2":
            raise ValueError(
                "--policy.memory_readers=span masks the attention to the memory frames, which flash-attn's "
                "kernel cannot take: use --policy.attn_implementation=sdpa or eager"
            )
        if self.state_frames not in ("all", "memory"):
            raise ValueError(f"--policy.state_frames must be all or memory, got {self.state_frames!r}")
        if self.state_frames == "memory" and not (self.use_state and self.uses_history):
            raise ValueError(
                "--policy.state_frames=memory gives the memory frames their state tokens and the current frame "
                f"none: it needs use_state=true and a memory (got use_state={self.use_state}, "
                f"memory={self.memory}, history={self.history}); without a memory, use --policy.use_state=false"
            )
        if self.memory_vision == "frozen" and (self.freeze_vision or not self.uses_history):
            raise ValueError(
                "--policy.memory_vision=frozen reads the memory frames through a frozen copy of the tower while "
                "the policy's own tower trains: it needs a memory (history > 0, memory not none) and "
                f"--policy.freeze_vision=false (got history={self.history}, memory={self.memory}, "
                f"freeze_vision={self.freeze_vision}; with a frozen tower the memory is read frozen already)"
            )
        memory_frozen = self.freeze_vision or self.memory_vision == "frozen"
        if self.vision_cache and not (memory_frozen and self.memory == "chunk" and self.history > 0):
            raise ValueError(
                "--policy.vision_cache holds a frozen tower's features of the chunk memory's frames: it needs "
                "--policy.freeze_vision=true or --policy.memory_vision=frozen, and memory=chunk with history "
                f"> 0 (got freeze_vision={self.freeze_vision}, memory_vision={self.memory_vision}, "
                f"memory={self.memory}, history={self.history})"
            )
        if self.vision_lr is not None and (self.vision_lr <= 0 or self.freeze_vision):
            raise ValueError(
                f"--policy.vision_lr is the training vision tower's learning rate: a number > 0 with "
                f"--policy.freeze_vision=false (got vision_lr={self.vision_lr}, freeze_vision={self.freeze_vision})"
            )
        if self.decision_place and self.think != "decision":
            raise ValueError(
                f"--policy.decision_place names the decided object's place in the think=decision target; "
                f"this policy has think={self.think!r}: set --policy.think=decision"
            )
        if self.decision_where and self.think != "decision":
            raise ValueError(
                f"--policy.decision_where says where the object acted on lies in the think=decision target; "
                f"this policy has think={self.think!r}: set --policy.think=decision"
            )
        if self.decision_layout and not self.decision_place:
            raise ValueError(
                "--policy.decision_layout lists the places the decision_place word is copied from; "
                "set --policy.decision_place=true with it"
            )
        if self.decision_token_weight != 1 and (self.think != "decision" or self.decision_token_weight <= 0):
            raise ValueError(
                f"--policy.decision_token_weight weighs the decision clause of the think=decision target "
                f"and must be > 0 (got {self.decision_token_weight} with think={self.think!r})"
            )
        if self.decision_weight <= 0 or self.decision_window < 1:
            raise ValueError(
                f"--policy.decision_weight must be > 0 and --policy.decision_window >= 1 (got "
                f"{self.decision_weight}, {self.decision_window})"
            )
        if self.opening_weight <= 0 or self.opening_window < 1:
            raise ValueError(
                f"--policy.opening_weight must be > 0 and --policy.opening_window >= 1 (got "
                f"{self.opening_weight}, {self.opening_window})"
            )
        if self.miss_weight < 0:
            raise ValueError(
                f"--policy.miss_weight must be >= 0 (0: the missed tries left out), got {self.miss_weight}"
            )
        # A local folder is stored absolute, so a checkpoint reloads from any working directory.
        for name in ("vlm_path", "dataset_root", "vision_cache"):
            value = getattr(self, name)
            if value and Path(value).expanduser().exists():
                setattr(self, name, str(Path(value).expanduser().resolve()))

    @property
    def autocast_bfloat16(self) -> bool:
        """Whether the forward passes run under bfloat16 autocast."""
        return self.dtype == "bfloat16" or (self.dtype == "auto" and str(self.device).startswith("cuda"))

    @property
    def uses_history(self) -> bool:
        return self.history > 0 and self.memory != "none"

    @property
    def observation_delta_indices(self) -> list[int] | None:
        # chunk memory reads its stride-16 history straight from the dataset; keyframe memories load
        # their frames through the annotation step (a per-sample set LeRobot's delta indices cannot express)
        # (with a vision cache the annotation step supplies the history by index: LeRobot reads the current frame)
        if self.memory == "chunk" and self.history > 0 and not self.vision_cache:
            return [-STRIDE * k for k in range(self.history, 0, -1)] + [0]
        return None

    @property
    def action_delta_indices(self) -> list[int]:
        return list(range(self.chunk_size))

    @property
    def reward_delta_indices(self) -> None:
        return None

    def get_optimizer_preset(self) -> AdamWConfig:
        return AdamWConfig(
            lr=self.optimizer_lr,
            betas=self.optimizer_betas,
            eps=self.optimizer_eps,
            weight_decay=self.optimizer_weight_decay,
            grad_clip_norm=self.optimizer_grad_clip_norm,
        )

    def get_scheduler_preset(self) -> CosineDecayWithWarmupSchedulerConfig:
        return CosineDecayWithWarmupSchedulerConfig(
            num_warmup_steps=self.scheduler_warmup_steps,
            num_decay_steps=self.scheduler_decay_steps,
            peak_lr=self.optimizer_lr,
            decay_lr=self.scheduler_decay_lr,
        )

    def validate_features(self) -> None:
        img = self.input_features.get(IMAGE_KEY)
        if img is None or img.type != FeatureType.VISUAL:
            raise ValueError(
                f"{self.type} needs the head camera {IMAGE_KEY!r}; input features were "
                f"{sorted(self.input_features)}"
            )
        if self.use_state and OBS_STATE not in self.input_features:
            raise ValueError(f"use_state=true needs {OBS_STATE!r} (or pass --policy.use_state=false)")
        act = self.output_features.get(ACTION)
        if act is None:
            raise ValueError(f"{self.type} needs an 'action' output feature")
        if self.fixed_view and self.action_dim != ACTION_DIM:
            raise ValueError(
                f"fixed_view=true drops the torso and head dimensions of the {ACTION_DIM}-D ActiveArena action; "
                f"this dataset's action is {self.action_dim}-D"
            )

    @property
    def action_dim(self) -> int:
        act = self.output_features.get(ACTION)
        return int(act.shape[0]) if act is not None else ACTION_DIM

    @property
    def predicted_action_dim(self) -> int:
        """The dimensions the head predicts: all, or (fixed_view) the arms' and grippers' 16."""
        return VIEW_DIMS.start if self.fixed_view else self.action_dim
