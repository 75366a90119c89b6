"""ActiveArena-VLA-GR00T's processors: the shared ones of ``activearena_vla`` (images through Qwen3-VL's
processor, prompt, think target, memory annotations; actions normalised)."""

from __future__ import annotations

from ..activearena_vla.processor_activearena_vla import make_activearena_vla_pre_post_processors


def make_activearena_groot_pre_post_processors(config, dataset_stats=None, dataset_meta=None):
    return make_activearena_vla_pre_post_processors(config, dataset_stats, dataset_meta)
