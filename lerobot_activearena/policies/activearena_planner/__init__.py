"""ActiveArena-Plan's planner (``activearena_planner``): its config, model, processors and answer
language (``answers``). The executor that runs it is ``activearena_plan``."""

from .configuration_activearena_planner import ActiveArenaPlannerConfig

__all__ = ["ActiveArenaPlannerConfig"]
