"""Config of ActiveArena-VLA-FAST (`fast_subtask_action_12_ws`): the OFT run's backbone, memory, state
tokens and optimiser (the shared ``activearena_vla`` fields) with the action queries and regression head
replaced by action tokens: the backbone's vocabulary grows by the FAST tokenizer's 2,048 ids and the
chunk is the text after ``<think>..</think><action>``, learned with one cross-entropy and decoded
greedily."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from lerobot.configs.policies import PreTrainedConfig
from lerobot.configs.types import NormalizationMode

from ..activearena_vla.configuration_activearena_vla import ActiveArenaVLAConfig

ACTION_TOKENIZER_DIR = "action_tokenizer"  # where a checkpoint keeps its FAST tokenizer


@PreTrainedConfig.register_subclass("activearena_fast")
@dataclass
class ActiveArenaFASTConfig(ActiveArenaVLAConfig):
    # The FAST tokenizer folder written by `activearena-fit-fast-tokenizer` (fitted on the training
    # dataset); it is saved into every checkpoint, which then loads its own copy.
    action_tokenizer_path: str | None = None
    action_vocab_size: int = 2048  # action tokens added to the backbone's vocabulary
    max_action_tokens: int = 96  # greedy decoding budget for the action span (p95 on the release: 26)
    # decode with the backbone's KV cache (tests check it yields the tokens of full re-encoding)
    kv_cache: bool = True
    # the whole response is one cross-entropy: the think text and the action tokens weigh the same
    lm_loss_weight: float = 1.0
    # FAST quantises chunks min-max normalised to [-1, 1] (as the tokenizer was fitted)
    normalization_mapping: dict[str, NormalizationMode] = field(
        default_factory=lambda: {
            "VISUAL": NormalizationMode.IDENTITY,
            "STATE": NormalizationMode.MEAN_STD,
            "ACTION": NormalizationMode.MIN_MAX,
        }
    )

    def __post_init__(self):
        super().__post_init__()
        if self.think == "none":
            raise ValueError(
                "activearena_fast decodes its actions after the <think> span; use --policy.think=subtask "
                "(the paper's run) or instruction"
            )
        if self.memory == "subtask":
            raise ValueError(
                "activearena_fast supports memory=chunk|motion|none: memory=subtask decodes the subtask "
                "separately (an OFT feature); FAST's subtask is part of its decoded response"
            )
        if self.fixed_view:
            raise ValueError(
                "activearena_fast has no fixed-view variant (ActiveArena-Fixed is an OFT preset)"
            )
        if self.lm_loss_weight != 1.0:
            raise ValueError(
                "activearena_fast's loss is one cross-entropy over think text and action tokens, so "
                "--policy.lm_loss_weight (the think loss's weight beside an action loss) has no effect: "
                f"leave it at 1.0, got {self.lm_loss_weight}"
            )
        if self.max_action_tokens < 1:
            raise ValueError(f"--policy.max_action_tokens must be >= 1, got {self.max_action_tokens}")
        if self.action_tokenizer_path and Path(self.action_tokenizer_path).expanduser().is_dir():
            self.action_tokenizer_path = str(Path(self.action_tokenizer_path).expanduser().resolve())
