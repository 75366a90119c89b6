"""ActiveArena-VLA-GR00T's processors: those of ``activearena_oft`` (the same inputs: images through
Qwen3-VL's processor, prompt, think target, memory annotations; actions normalised)."""

from __future__ import annotations

from ..activearena_oft.processor_activearena_oft import make_activearena_oft_pre_post_processors


def make_activearena_groot_pre_post_processors(config, dataset_stats=None, dataset_meta=None):
    return make_activearena_oft_pre_post_processors(config, dataset_stats, dataset_meta)
