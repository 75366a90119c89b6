"""ActiveArena-Plan's executor processors: the shared ones of ``activearena_vla`` with the paper's
executor prompt. The executor is prompted with the annotated subtask at training time (at evaluation
the policy re-prompts it with its planner's)."""

from __future__ import annotations

from ..activearena_vla.processor_activearena_vla import ASSISTANT, make_activearena_vla_pre_post_processors
from .memory_bank import executor_prompt

EXECUTOR_PROMPT = executor_prompt("{instruction}") + ASSISTANT


def make_activearena_plan_pre_post_processors(config, dataset_stats=None, dataset_meta=None):
    return make_activearena_vla_pre_post_processors(
        config, dataset_stats, dataset_meta, prompt_template=EXECUTOR_PROMPT, subtask_prompt=True
    )
