"""Record one expert episode for a dataset: run it with head-camera rendering, derive the keyframe
columns, and yield LeRobot frames."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import asdict, dataclass

import numpy as np

from ..annotations.keyframes import chunk_keyframes, motion_keyframes, subtask_keyframes
from ..episodes.rollout import DemoVariation, EpisodeResult, run_expert_episode
from ..sim.scene import HEAD_SIZE
from .features import frame_row


@dataclass
class RecordedEpisode:
    result: EpisodeResult
    images: list[np.ndarray]
    keyframes: dict[str, np.ndarray]

    def rows(self, features: dict[str, dict]) -> Iterator[dict]:
        r = self.result
        instruction = r.sidecar["instruction"]
        for t, frame in enumerate(r.frames):
            kf = {name: int(k[t]) for name, k in self.keyframes.items()}
            yield frame_row(frame, r.states[t], r.actions[t], self.images[t], kf, instruction, features)


def episode_keyframes(result: EpisodeResult) -> dict[str, np.ndarray]:
    subtask = np.array([int(f["subtask"]) for f in result.frames])
    return {
        "subtask_keyframe": subtask_keyframes(subtask),
        "motion_keyframe": motion_keyframes(result.states),
        "chunk_keyframe": chunk_keyframes(result.length),
    }


def record_episode(
    task: str,
    seed: int,
    split: str,
    image_size: tuple[int, int] = HEAD_SIZE,
    variation: DemoVariation = DemoVariation(),
) -> RecordedEpisode:
    """Run the expert and keep the head image of every frame (the frame the annotation describes),
    rendered at ``image_size`` (height, width), its demonstrations varied by ``variation``."""
    images: list[np.ndarray] = []
    result = run_expert_episode(
        task,
        seed,
        split,
        on_frame=lambda t, sim, frame, action: images.append(sim.render_head()),
        image_size=image_size,
        **asdict(variation),
    )
    keyframes = episode_keyframes(result) if result.success else {}
    return RecordedEpisode(result, images, keyframes)
