"""`activearena_expert`: the scripted expert played inside lerobot-eval (the benchmark's upper row)."""

from .configuration_activearena_expert import ActiveArenaExpertConfig

__all__ = ["ActiveArenaExpertConfig"]
