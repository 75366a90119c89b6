"""ActiveArena-VLA-FAST's processors: the shared ones of ``activearena_vla`` with the think target followed by
``<action>`` (the policy appends the chunk's action tokens and ``</action>``), plus one step that
writes the current state in the action's normalisation: the command the policy holds when a
response does not decode to a chunk before it has issued any."""

from __future__ import annotations

from dataclasses import dataclass

import torch
from lerobot.configs.types import FeatureType, PipelineFeatureType, PolicyFeature
from lerobot.lerobot_types import TransitionKey
from lerobot.processor import ProcessorStep, ProcessorStepRegistry
from lerobot.processor.normalize_processor import _NormalizationMixin
from lerobot.utils.constants import ACTION

from ..activearena_vla.processor_activearena_vla import (
    RAW_STATE,
    VLM,
    make_activearena_vla_pre_post_processors,
)

HOLD_COMMAND = VLM + "hold_command"
THINK_THEN_ACTION = "<think>{target}</think><action>"
ACTION_SUFFIX = "</action><|im_end|>"


@ProcessorStepRegistry.register(name="activearena_fast_hold_command")
@dataclass
class HoldCommandStep(_NormalizationMixin, ProcessorStep):
    """The current (raw) state normalised with the *action's* statistics (state and action share the
    18-D joint layout), so holding it keeps the robot where it is. The mixin is LeRobot's normaliser,
    used through its private name as no public route takes one key's statistics for another."""

    def __call__(self, transition):
        obs = transition.get(TransitionKey.OBSERVATION)
        if obs is None or RAW_STATE not in obs:
            return transition
        state = torch.as_tensor(obs[RAW_STATE])
        state = state[:, -1] if state.dim() == 3 else state  # a dataset batch with history: the current
        obs = dict(obs)
        obs[HOLD_COMMAND] = self._apply_transform(state, ACTION, FeatureType.ACTION)
        out = dict(transition)
        out[TransitionKey.OBSERVATION] = obs
        return out

    def transform_features(self, features: dict[PipelineFeatureType, dict[str, PolicyFeature]]):
        return features


def make_activearena_fast_pre_post_processors(config, dataset_stats=None, dataset_meta=None):
    hold = HoldCommandStep(
        features={ACTION: config.output_features[ACTION]},
        norm_map=config.normalization_mapping,
        stats=dataset_stats,
        device=config.device,
    )
    return make_activearena_vla_pre_post_processors(
        config,
        dataset_stats,
        dataset_meta,
        think_template=THINK_THEN_ACTION,
        after_normalize=(hold,),
    )
