"""ActiveArena-Plan (`oft_subtask_planned_12_ws`): the OFT executor (``activearena_plan``) that runs its
planner (``activearena_planner``, its own package) at evaluation, its prompt and run-time memory bank
(``memory_bank``)."""

from .configuration_activearena_plan import ActiveArenaPlanConfig

__all__ = ["ActiveArenaPlanConfig"]
