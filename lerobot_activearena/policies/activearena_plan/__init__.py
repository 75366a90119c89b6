"""ActiveArena-Plan (`oft_subtask_planned_12_ws`): the planner (``activearena_planner``) and the OFT
executor (``activearena_plan``, which runs its planner at evaluation), their prompts, targets,
retrieval labels and run-time memory bank (``planning``)."""

from .configuration_activearena_plan import ActiveArenaPlanConfig, ActiveArenaPlannerConfig

__all__ = ["ActiveArenaPlanConfig", "ActiveArenaPlannerConfig"]
