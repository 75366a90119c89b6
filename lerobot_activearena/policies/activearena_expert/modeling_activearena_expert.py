"""The oracle policy: returns the scripted expert's next action that the env exposes through its
opt-in privileged channel (``observation.environment_state``)."""

from __future__ import annotations

import torch
from lerobot.policies.pretrained import PreTrainedPolicy
from lerobot.utils.constants import OBS_ENV_STATE
from torch import Tensor, nn

from .configuration_activearena_expert import ACTION_DIM, ActiveArenaExpertConfig


class ActiveArenaExpertPolicy(PreTrainedPolicy):
    config_class = ActiveArenaExpertConfig
    name = "activearena_expert"

    def __init__(self, config: ActiveArenaExpertConfig, **kwargs):
        super().__init__(config)
        config.validate_features()
        self.config = config
        self.register_buffer("_device_anchor", torch.zeros(1), persistent=False)
        self._unused = nn.Identity()

    def get_optim_params(self) -> list:
        return []

    def reset(self) -> None:
        pass

    def forward(self, batch: dict[str, Tensor]):
        raise NotImplementedError("activearena_expert is the scripted expert; it has nothing to train")

    @torch.no_grad()
    def predict_action_chunk(self, batch: dict[str, Tensor], **kwargs) -> Tensor:
        return self.select_action(batch)[:, None, :]

    @torch.no_grad()
    def select_action(self, batch: dict[str, Tensor], **kwargs) -> Tensor:
        if OBS_ENV_STATE not in batch:
            raise KeyError(
                f"{OBS_ENV_STATE} is missing: enable the env's privileged channel with "
                "--env.expert_channel=true"
            )
        action = batch[OBS_ENV_STATE]
        if action.shape[-1] != ACTION_DIM:
            raise ValueError(f"expected an {ACTION_DIM}-D expert action, got shape {tuple(action.shape)}")
        return action.reshape(-1, ACTION_DIM)
