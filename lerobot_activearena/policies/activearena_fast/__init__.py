"""`activearena_fast`: ActiveArena-VLA's FAST run (`fast_subtask_action_12_ws`): the OFT run's backbone
and memory with actions as FAST tokens (``action_tokenizer``, fitted by
``activearena-fit-fast-tokenizer``) in the backbone's extended vocabulary."""

from .configuration_activearena_fast import ActiveArenaFASTConfig

__all__ = ["ActiveArenaFASTConfig"]
