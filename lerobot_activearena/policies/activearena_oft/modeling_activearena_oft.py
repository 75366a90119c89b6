"""ActiveArena-VLA-OFT: the shared ActiveArena-VLA policy with the OFT head: 16 action-query positions
after the prompt feed an MLPResNet that regresses a 16 x 18 chunk with L1 (the ``<think>`` span after
the queries is trained with next-token loss, weight 0.1; with ``think_first`` the span comes before the
queries and the policy decodes it before it acts)."""

from __future__ import annotations

import torch
from lerobot.utils.constants import ACTION
from torch import Tensor, nn

from ..activearena_vla.helpers import real_steps
from ..activearena_vla.modeling_activearena_vla import QUERY, ActiveArenaVLAPolicy
from ..activearena_vla.processor_activearena_vla import FRAME_VALID
from .configuration_activearena_oft import ActiveArenaOFTConfig
from .heads import MLPResNet


class ActiveArenaOFTPolicy(ActiveArenaVLAPolicy):
    config_class = ActiveArenaOFTConfig
    name = "activearena_oft"

    def build_action_head(self, width: int) -> None:
        self.action_queries = nn.Parameter(torch.randn(self.config.chunk_size, width) * 0.02)
        self.head = MLPResNet(
            width,
            self.config.head_hidden_mult * width,
            self.config.predicted_action_dim,
            self.config.head_blocks,
        )

    @property
    def n_queries(self) -> int:
        """Action query tokens after the prompt: one per chunk step."""
        return self.config.chunk_size

    @property
    def think_first(self) -> bool:
        return self.config.think_first

    def decode_actions(self, hidden: Tensor, kind: Tensor) -> Tensor:
        """The (B, chunk, predicted_action_dim) prediction from the last-layer states at the action queries."""
        return self.head(hidden[kind == QUERY].view(kind.shape[0], self.config.chunk_size, -1).float())

    def action_loss(self, hidden: Tensor, kind: Tensor, batch: dict[str, Tensor]) -> tuple[Tensor, dict]:
        """Per-sample L1 over the chunk's real (not padded) steps."""
        pred = self.decode_actions(hidden, kind).float()
        target = batch[ACTION][..., : self.config.predicted_action_dim]
        keep = real_steps(batch, target)
        l1 = (pred - target).abs().mean(-1)
        l1 = (l1 * keep).sum(-1) / keep.sum(-1).clamp(min=1)
        return l1, {"l1_loss": float(l1.detach().mean())}

    # ----- the subtask write policy (memory=subtask, the paper's OFT ablation) -----
    # At evaluation the policy decodes its own current subtask after ``<think>`` at every chunk
    # boundary (in the pass that yields the chunk) and writes a frame where that subtask changes.
    def start_episode(self, batch: dict[str, Tensor]) -> None:
        if self.config.memory == "subtask" and self.config.uses_history and self.config.think != "subtask":
            raise ValueError(
                "memory=subtask at evaluation writes a frame when the policy's own predicted subtask "
                "changes, so it needs a policy trained with think=subtask"
            )
        super().start_episode(batch)
        batch_size = batch[FRAME_VALID].shape[0]
        self._subtask: list[tuple[int, ...] | None] = [None] * batch_size
        self._subtask_new = [False] * batch_size

    def predicted_subtask(self, b: int = 0) -> tuple[int, ...] | None:
        """Env ``b``'s last decoded subtask (token ids up to ``</think>``); None before any decoding."""
        return None if self._bank is None else self._subtask[b]

    def predict_chunk(self, encode_args: tuple, vision_cache: dict | None = None) -> Tensor:
        if self.think_first:
            return self.think_then_act(encode_args, vision_cache=vision_cache)[1]
        if self.config.memory != "subtask" or not self.config.uses_history:
            return super().predict_chunk(encode_args, vision_cache)
        subtasks, pred = self.predict_subtask_and_actions(encode_args, vision_cache=vision_cache)
        for b, sub in enumerate(subtasks):
            self._subtask_new[b] = sub != self._subtask[b]  # first frame of a new (predicted) subtask
            self._subtask[b] = sub
        return pred

    def writes_frame(self, b: int) -> bool:
        if self.config.memory == "subtask":  # decided at chunk boundaries, where the subtask is predicted
            new, self._subtask_new[b] = self._subtask_new[b], False
            return new
        return super().writes_frame(b)

    @torch.no_grad()
    def predict_subtask(self, encode_args: tuple) -> list[tuple[int, ...]]:
        """Greedy ``<think>`` decoding: the token ids of each sample's predicted current subtask (up to and
        including ``</think>``). It decides which frames the subtask memory keeps; the actions never read it."""
        return self.greedy_think(encode_args)[0]

    @torch.no_grad()
    def predict_subtask_and_actions(
        self, encode_args: tuple, vision_cache: dict | None = None
    ) -> tuple[list[tuple[int, ...]], Tensor]:
        """The predicted subtasks and the action chunk from one backbone pass over images and prompt: the
        queries sit before ``<think>``, so (causal attention) the actions are those of ``encode``."""
        tokens, _, actions = self.greedy_think(encode_args, vision_cache=vision_cache)
        return tokens, actions

    def greedy_think(
        self, encode_args: tuple, use_cache: bool = True, vision_cache: dict | None = None
    ) -> tuple[list[tuple[int, ...]], list[Tensor], Tensor]:
        """Greedy decoding after ``<think>`` up to ``</think>``; returns the tokens, each step's (B, vocab)
        logits and the action chunk read from the first pass's query positions."""
        start, end = self.think_token_ids()
        tokens, step_logits, (hidden, kind) = self.greedy_decode(
            encode_args, [start], end, self.config.subtask_max_tokens, use_cache, vision_cache
        )
        return tokens, step_logits, self.decode_actions(hidden, kind)

    # ----- think first: the actions read the policy's own decoded span -----
    @torch.no_grad()
    def think_then_act(
        self, encode_args: tuple, vision_cache: dict | None = None
    ) -> tuple[list[tuple[int, ...]], Tensor]:
        """Greedy ``<think>`` decoding (images and prompt only), then the chunk from a pass with the decoded
        span before the queries, closed as in training (``</think>``, end of turn). Returns each sample's
        decoded tokens (up to and including ``</think>``) and the (B, chunk, predicted_action_dim) chunk."""
        start, end = self.think_token_ids()
        tokens, _, _ = self.greedy_decode(
            encode_args, [start], end, self.config.subtask_max_tokens, vision_cache=vision_cache
        )
        close = [end, self.text_tokenizer.convert_tokens_to_ids("<|im_end|>")]
        spans = [[start, *t[:-1], *close] if t and t[-1] == end else [start, *t, *close] for t in tokens]
        width = max(len(s) for s in spans)
        think = torch.full((len(spans), width), self.pad_id, dtype=torch.long)
        mask = torch.zeros_like(think, dtype=torch.bool)
        for b, span in enumerate(spans):
            think[b, : len(span)], mask[b, : len(span)] = torch.tensor(span), True
        return tokens, self.encode(*encode_args, think, mask, vision_cache=vision_cache)[0]
