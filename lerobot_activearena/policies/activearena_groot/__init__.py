"""`activearena_groot`: ActiveArena-VLA's GR00T run (`gr00t_subtask_action_12_ws`): the OFT run's
backbone and memory with a flow-matching DiT action head (``flow_dit``)."""

from .configuration_activearena_groot import ActiveArenaGR00TConfig

__all__ = ["ActiveArenaGR00TConfig"]
