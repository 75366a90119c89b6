"""ActiveArena-Plan's planner (``activearena_planner``): the shared VLA base without an action head,
trained on its answer's cross-entropy only; ``plan`` decodes an answer greedily. It is run by the
executor (``activearena_plan``), not evaluated on its own."""

from __future__ import annotations

import torch
from torch import Tensor

from ..activearena_vla.helpers import in_precision
from ..activearena_vla.modeling_activearena_vla import ActiveArenaVLAPolicy
from .configuration_activearena_planner import ActiveArenaPlannerConfig


class ActiveArenaPlannerPolicy(ActiveArenaVLAPolicy):
    config_class = ActiveArenaPlannerConfig
    name = "activearena_planner"

    def build_action_head(self, width: int) -> None:
        pass  # the planner answers in text

    @property
    def n_queries(self) -> int:
        return 0

    def get_optim_params(self) -> list[dict]:
        return [g for g in super().get_optim_params() if g["params"]]

    @in_precision
    def forward(self, batch: dict[str, Tensor], reduction: str = "mean"):
        if reduction != "mean":
            raise ValueError("activearena_planner's loss is one cross-entropy over the batch's tokens")
        ce = self.hidden_states(*self.training_args(batch))[2]
        return ce, {"lm_loss": float(ce.detach())}

    @torch.no_grad()
    def plan(self, encode_args: tuple, vision_cache: dict | None = None) -> list[str]:
        """Each sample's greedy answer, from ``<think>`` (the prompt's images are ``encode_args``)."""
        tok = self.text_tokenizer
        start, stop = self.think_token_ids()[0], tok.convert_tokens_to_ids("<|im_end|>")
        answers = self.greedy_decode(
            encode_args, [start], stop, self.config.plan_max_tokens, True, vision_cache
        )[0]
        return [
            "<think>" + tok.decode([t for t in ids if t != stop], skip_special_tokens=False)
            for ids in answers
        ]

    def select_action(self, batch: dict[str, Tensor], **kwargs) -> Tensor:
        raise TypeError(
            "activearena_planner answers with a subtask and retrievals, not actions: evaluate the executor "
            "(--policy.path=<activearena_plan checkpoint>), which loads this planner via --policy.planner_path"
        )

    predict_action_chunk = select_action
