"""ActiveArena-VLA-OFT's processors: the shared ActiveArena-VLA pipelines (saved with the checkpoint,
so ``lerobot-eval --policy.path=...`` rebuilds them with no extra flags)."""

from __future__ import annotations

from ..activearena_vla.processor_activearena_vla import make_activearena_vla_pre_post_processors


def make_activearena_oft_pre_post_processors(config, dataset_stats=None, dataset_meta=None):
    return make_activearena_vla_pre_post_processors(config, dataset_stats, dataset_meta)
