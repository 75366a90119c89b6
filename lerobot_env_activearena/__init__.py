"""Discovery shim: LeRobot imports installed ``lerobot_env_*`` distributions by name
(``register_third_party_plugins``); importing this registers ``--env.type=activearena`` and the
policy types ``activearena_expert``, ``activearena_oft``, ``activearena_groot``, ``activearena_fast``,
``activearena_planner``, ``activearena_plan`` and ``activearena_remote``."""

from lerobot_activearena.envs import configs as env_configs
from lerobot_activearena.policies import (
    activearena_expert,
    activearena_fast,
    activearena_groot,
    activearena_oft,
    activearena_plan,
    activearena_planner,
    activearena_remote,
)

__all__ = [
    "activearena_expert",
    "activearena_fast",
    "activearena_groot",
    "activearena_oft",
    "activearena_plan",
    "activearena_planner",
    "activearena_remote",
    "env_configs",
]
