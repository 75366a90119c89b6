"""Config of a remote policy: where its server is, which protocol it speaks, how many steps of each
returned chunk to execute, and how long to wait. No weights live here."""

from __future__ import annotations

from dataclasses import dataclass, field

from lerobot.configs.policies import PreTrainedConfig
from lerobot.configs.types import NormalizationMode
from lerobot.optim.optimizers import AdamWConfig
from lerobot.utils.constants import OBS_STATE

IMAGE_KEY = "observation.images.head"
PROTOCOLS = ("openpi", "vla_eval")


@PreTrainedConfig.register_subclass("activearena_remote")
@dataclass
class ActiveArenaRemoteConfig(PreTrainedConfig):
    # The policy server, e.g. ws://gpu-node:8000 (openpi: `scripts/serve_policy.py --port 8000`).
    url: str = "ws://localhost:8000"
    # Wire protocol: openpi (openpi_client.websocket_client_policy's messages) | vla_eval (allenai's harness).
    protocol: str = "openpi"
    # Steps of each returned action chunk executed before the server is asked again (1..chunk length).
    n_action_steps: int = 8
    # Seconds to wait for the connection, and for each answer, before the episode fails with an error.
    connect_timeout_s: float = 30.0
    timeout_s: float = 60.0
    n_obs_steps: int = 1  # the features come from the env (lerobot-eval's make_policy fills them)
    normalization_mapping: dict[str, NormalizationMode] = field(
        default_factory=lambda: {
            "VISUAL": NormalizationMode.IDENTITY,
            "STATE": NormalizationMode.IDENTITY,
            "ACTION": NormalizationMode.IDENTITY,
        }
    )
    push_to_hub: bool = False

    def __post_init__(self):
        super().__post_init__()
        if self.protocol not in PROTOCOLS:
            raise ValueError(f"--policy.protocol must be one of {PROTOCOLS}, got {self.protocol!r}")
        if not self.url.startswith(("ws://", "wss://")):
            raise ValueError(f"--policy.url must be a websocket address (ws://HOST:PORT), got {self.url!r}")
        if self.n_action_steps < 1:
            raise ValueError(f"--policy.n_action_steps must be >= 1, got {self.n_action_steps}")
        if self.timeout_s <= 0 or self.connect_timeout_s <= 0:
            raise ValueError("--policy.timeout_s and --policy.connect_timeout_s must be > 0")

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
        return AdamWConfig(lr=0.0)  # nothing to train here; LeRobot asks every config for one

    def get_scheduler_preset(self) -> None:
        return None

    def validate_features(self) -> None:
        missing = [k for k in (IMAGE_KEY, OBS_STATE) if k not in self.input_features]
        if missing:
            raise ValueError(
                f"activearena_remote sends the head image and the state; the env gave no {missing} "
                f"(input features were {sorted(self.input_features)})"
            )
