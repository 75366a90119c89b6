"""Config of the oracle policy: no weights, no training; it needs the env's privileged expert channel."""

from __future__ import annotations

from dataclasses import dataclass, field

from lerobot.configs.policies import PreTrainedConfig
from lerobot.configs.types import NormalizationMode
from lerobot.optim.optimizers import AdamWConfig
from lerobot.utils.constants import OBS_ENV_STATE

from ...sim.action import ACTION_DIM


@PreTrainedConfig.register_subclass("activearena_expert")
@dataclass
class ActiveArenaExpertConfig(PreTrainedConfig):
    n_obs_steps: int = 1
    normalization_mapping: dict[str, NormalizationMode] = field(
        default_factory=lambda: {
            "VISUAL": NormalizationMode.IDENTITY,
            "STATE": NormalizationMode.IDENTITY,
            "ENV": NormalizationMode.IDENTITY,
            "ACTION": NormalizationMode.IDENTITY,
        }
    )

    @property
    def observation_delta_indices(self) -> None:
        return None

    @property
    def action_delta_indices(self) -> None:
        return None

    @property
    def reward_delta_indices(self) -> None:
        return None

    def get_optimizer_preset(self) -> AdamWConfig:
        return AdamWConfig(lr=0.0)  # nothing to train; present because LeRobot asks every config

    def get_scheduler_preset(self) -> None:
        return None

    def validate_features(self) -> None:
        feat = self.input_features.get(OBS_ENV_STATE)
        if feat is None or tuple(feat.shape) != (ACTION_DIM,):
            raise ValueError(
                "activearena_expert plays the scripted expert and needs its privileged channel: run "
                "lerobot-eval with --env.type=activearena --env.expert_channel=true "
                f"(input features were {sorted(self.input_features)})"
            )
