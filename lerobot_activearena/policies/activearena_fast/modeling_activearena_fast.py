"""ActiveArena-VLA-FAST: the shared ActiveArena-VLA policy (``activearena_vla``: backbone, memory
bank, state tokens, evaluation loop) whose actions are text. The backbone's vocabulary grows by the FAST tokenizer's ids; the target
after the prompt is ``<think>{subtask}</think><action>{action tokens}</action><|im_end|>``, learned with
one cross-entropy. At evaluation the response is decoded greedily; one that does not spell a
16 x 18 chunk never stops the episode: that env holds its last command (before its first, its
current state) for the chunk, and the failure is counted (``rollout_stats``)."""

from __future__ import annotations

import functools
import logging
import os
from pathlib import Path

import numpy as np
import torch
from lerobot.utils.constants import ACTION
from torch import Tensor

from ..activearena_vla.helpers import in_precision
from ..activearena_vla.modeling_activearena_vla import ActiveArenaVLAPolicy
from .action_tokenizer import FastActionTokenizer
from .configuration_activearena_fast import ACTION_TOKENIZER_DIR, ActiveArenaFASTConfig
from .processor_activearena_fast import ACTION_SUFFIX, HOLD_COMMAND

log = logging.getLogger(__name__)


class ActiveArenaFASTPolicy(ActiveArenaVLAPolicy):
    config_class = ActiveArenaFASTConfig
    name = "activearena_fast"

    # ----- the action vocabulary (replaces OFT's queries and head) -----
    def build_action_head(self, width: int) -> None:
        c = self.config
        if not c.action_tokenizer_path:
            raise ValueError(
                "activearena_fast needs its action tokenizer: fit one on the training dataset with "
                "`activearena-fit-fast-tokenizer --repo-id ID --root DIR --out TOK` and pass "
                "--policy.action_tokenizer_path=TOK"
            )
        tok = FastActionTokenizer.from_pretrained(c.action_tokenizer_path)
        if (tok.horizon, tok.action_dim) != (c.chunk_size, c.predicted_action_dim):
            raise ValueError(
                f"the action tokenizer at {c.action_tokenizer_path} spells {tok.horizon} x {tok.action_dim} "
                f"chunks; this policy's are {c.chunk_size} x {c.predicted_action_dim}"
            )
        if tok.vocab_size > c.action_vocab_size:
            raise ValueError(
                f"the action tokenizer has {tok.vocab_size} ids, more than --policy.action_vocab_size "
                f"({c.action_vocab_size})"
            )
        self.action_tokenizer = tok
        self.action_token_base = self.vlm.get_input_embeddings().weight.shape[0]  # after every text id
        self.vlm.resize_token_embeddings(self.action_token_base + c.action_vocab_size)

    @property
    def n_queries(self) -> int:
        return 0

    def action_token_ids(self, chunk: np.ndarray) -> list[int]:
        """A normalised (chunk, action_dim) chunk as backbone ids."""
        return [self.action_token_base + i for i in self.action_tokenizer.encode(chunk)]

    def decode_response(self, ids) -> np.ndarray | None:
        """The chunk spelled by a generated response's action tokens, or None when they are missing,
        interrupted by text, or do not decode to exactly one chunk."""
        base, end = self.action_token_base, self.action_token_base + self.config.action_vocab_size
        where = [i for i, t in enumerate(ids) if base <= t < end]
        if not where or where != list(range(where[0], where[-1] + 1)):
            return None
        return self.action_tokenizer.decode([ids[i] - base for i in where])

    @functools.cached_property
    def _action_suffix_ids(self) -> list[int]:
        """``</action><|im_end|>`` in the backbone's tokens (tokenised once, not every step)."""
        return self.text_tokenizer(ACTION_SUFFIX, add_special_tokens=False)["input_ids"]

    # ----- training: one cross-entropy over think text and action tokens -----
    def training_args(self, batch: dict[str, Tensor]) -> tuple:
        args = list(super().training_args(batch))
        think, mask = args[7], args[8]
        if think is None:
            raise ValueError("activearena_fast trains on the think target: the batch has no think ids")
        target = batch[ACTION][..., : self.config.predicted_action_dim].float().cpu().numpy()
        suffix = self._action_suffix_ids
        spans = [
            think[b][mask[b]].tolist() + self.action_token_ids(target[b]) + suffix for b in range(len(target))
        ]
        ids = torch.full((len(spans), max(map(len, spans))), self.pad_id, dtype=torch.long)
        keep = torch.zeros_like(ids, dtype=torch.bool)
        for b, s in enumerate(spans):
            ids[b, : len(s)], keep[b, : len(s)] = torch.tensor(s), True
        args[7], args[8] = ids, keep
        return tuple(args)

    @in_precision
    def forward(self, batch: dict[str, Tensor], reduction: str = "mean"):
        if reduction != "mean":
            raise ValueError(
                "activearena_fast's loss is one cross-entropy over the batch's tokens (reduction=mean)"
            )
        ce = self.hidden_states(*self.training_args(batch))[2]
        return ce, {"ce_loss": float(ce.detach())}

    # ----- evaluation -----
    def decode(self, encode_args: tuple, use_cache: bool | None = None, vision_cache: dict | None = None):
        """Greedy responses after ``<think>``: each sample's token ids (up to ``<|im_end|>``)."""
        start = self.think_token_ids()[0]
        stop = self.text_tokenizer.convert_tokens_to_ids("<|im_end|>")
        budget = self.config.subtask_max_tokens + self.config.max_action_tokens + 8  # + the tags
        use_cache = self.config.kv_cache if use_cache is None else use_cache
        return self.greedy_decode(encode_args, [start], stop, budget, use_cache, vision_cache)[0]

    def encode(self, *args, vision_cache: dict | None = None) -> tuple[Tensor, None]:
        """The decoded (B, chunk, action_dim) chunks; NaN rows where a response did not decode."""
        responses = self.decode(args, vision_cache=vision_cache)
        shape = (len(responses), self.config.chunk_size, self.config.predicted_action_dim)
        pred = torch.full(shape, float("nan"))
        for b, ids in enumerate(responses):
            chunk = self.decode_response(ids)
            if chunk is not None:
                pred[b] = torch.from_numpy(chunk).float()
        return pred.to(self.device), None

    def reset(self) -> None:
        stats = getattr(self, "_decode_stats", None)
        if stats and sum(stats["failed_decodes"]):
            log.warning(
                "activearena_fast: %d of %d chunks did not decode to a chunk; each env held its last "
                "command for them",
                sum(stats["failed_decodes"]),
                sum(stats["chunks"]),
            )
        super().reset()
        self._last_command: Tensor | None = None
        self._decode_stats: dict[str, list[int]] | None = None

    def rollout_stats(self) -> list[dict[str, int]]:
        """Per env since the last reset: chunks decoded and responses that did not decode."""
        s = self._decode_stats or {"chunks": [], "failed_decodes": []}
        return [
            {"chunks": c, "failed_decodes": f} for c, f in zip(s["chunks"], s["failed_decodes"], strict=True)
        ]

    @torch.no_grad()
    def predict_action_chunk(self, batch: dict[str, Tensor], **kwargs) -> Tensor:
        pred = super().predict_action_chunk(batch, **kwargs)
        failed = torch.isnan(pred).flatten(1).any(1)
        batch_size = pred.shape[0]
        if self._decode_stats is None:
            self._decode_stats = {"chunks": [0] * batch_size, "failed_decodes": [0] * batch_size}
        hold = self._last_command if self._last_command is not None else batch[HOLD_COMMAND].float()
        for b in range(batch_size):
            self._decode_stats["chunks"][b] += 1
            if failed[b]:
                if not sum(self._decode_stats["failed_decodes"]):
                    log.warning(
                        "activearena_fast: a response did not decode to a %d x %d chunk; the env holds its last "
                        "command (failures are counted per episode: policy_stats in activearena-eval records)",
                        *pred.shape[1:],
                    )
                self._decode_stats["failed_decodes"][b] += 1
                pred[b] = hold[b].to(pred)[None, : pred.shape[-1]]
        self._last_command = pred[:, self.config.n_action_steps - 1].clone()
        return pred

    def _save_pretrained(self, save_directory: Path, state_dict=None) -> None:
        super()._save_pretrained(save_directory, state_dict=state_dict)
        self.action_tokenizer.save_pretrained(Path(save_directory) / ACTION_TOKENIZER_DIR)

    @classmethod
    def from_pretrained(cls, pretrained_name_or_path, *, config=None, **kwargs):
        """As LeRobot's, with the checkpoint's own action tokenizer (a local folder or a Hub repo)."""
        from lerobot.configs.policies import PreTrainedConfig

        if config is None:
            config = PreTrainedConfig.from_pretrained(pretrained_name_or_path)
        path = str(pretrained_name_or_path)
        if os.path.isdir(path):
            folder = Path(path) / ACTION_TOKENIZER_DIR
        else:
            from huggingface_hub import snapshot_download

            folder = (
                Path(snapshot_download(path, allow_patterns=[f"{ACTION_TOKENIZER_DIR}/*"]))
                / ACTION_TOKENIZER_DIR
            )
        if folder.is_dir():
            config.action_tokenizer_path = str(folder)
        return super().from_pretrained(pretrained_name_or_path, config=config, **kwargs)
