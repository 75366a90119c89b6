"""`activearena_oft`: ActiveArena-VLA with Qwen3-VL, an OFT action head and perceptual memory."""

from .configuration_activearena_oft import ActiveArenaOFTConfig

__all__ = ["ActiveArenaOFTConfig"]
