"""ActiveArena-Plan's planner processors: the shared ones of ``activearena_vla`` with the paper's planner
prompt; the annotation step also writes the planner's complete training target (the subtask and the
retrieval positions of its input frames)."""

from __future__ import annotations

from dataclasses import dataclass

import torch
from lerobot.lerobot_types import TransitionKey
from lerobot.processor import ProcessorStepRegistry

from ...annotations.keyframes import retrieval_positions
from ..activearena_vla.processor_activearena_vla import (
    ASSISTANT,
    ActiveArenaAnnotationStep,
    make_activearena_vla_pre_post_processors,
)
from .answers import planner_prompt, planner_target, stride_frames

PLANNER_PROMPT = planner_prompt("{instruction}") + ASSISTANT
PLANNER_TARGET = "{target}<|im_end|>"


@ProcessorStepRegistry.register(name="activearena_planner_annotations")
@dataclass
class PlannerAnnotationStep(ActiveArenaAnnotationStep):
    """Training only: also writes the planner's target for each sample's stride-16 input frames."""

    def __call__(self, transition):
        out = super().__call__(transition)
        comp = out.get(TransitionKey.COMPLEMENTARY_DATA) or {}
        if comp.get("index") is None or "subtask" not in comp:
            return out
        targets = []
        for i, subtask in zip(
            torch.as_tensor(comp["index"]).reshape(-1).tolist(), comp["subtask"], strict=True
        ):
            x, keyframes = self._ann.subtask_keyframes(i)
            frames = stride_frames(x, history=self.history)
            targets.append(planner_target(len(frames), subtask, retrieval_positions(frames, keyframes)))
        out = dict(out)
        out[TransitionKey.COMPLEMENTARY_DATA] = {**comp, "think_target": targets}
        return out


def make_activearena_planner_pre_post_processors(config, dataset_stats=None, dataset_meta=None):
    return make_activearena_vla_pre_post_processors(
        config,
        dataset_stats,
        dataset_meta,
        think_template=PLANNER_TARGET,
        prompt_template=PLANNER_PROMPT,
        annotation_step=PlannerAnnotationStep,
    )
