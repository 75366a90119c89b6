"""The per-frame annotation writer: the paper's schema from the simulator, the perception memory
and what the expert declares (``Intent``), plus the stage transitions of the episode sidecar."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..sim.action import TORSO_YAW
from ..sim.perception import PerceptionMemory
from ..sim.simulator import ActiveArenaSim
from .schema import CAMERA_HOLD, FRAME_FIELDS, STAGE_NAMES, STAGE_SEARCH


@dataclass
class Intent:
    """What the expert is doing now; the expert updates it, the writer writes it every frame."""

    subtask: int = 1
    stage: int = STAGE_SEARCH
    focus: int = -1
    info_complete: bool = False
    camera_mode: int = CAMERA_HOLD
    camera_target_theta: float = math.nan  # planned heading (deg) while the camera moves, else NaN
    search_targets: set[int] = field(default_factory=set)
    action_targets: set[int] = field(default_factory=set)
    carried: set[int] = field(default_factory=set)


class AnnotationWriter:
    """Emits the paper's per-frame schema; visibility comes from the episode's perception memory."""

    def __init__(self, sim: ActiveArenaSim, perception: PerceptionMemory):
        self.sim, self.perception = sim, perception
        self.n = perception.n
        self.transitions: list[dict] = []
        self._last_key: tuple | None = None

    def _mask(self, idx: set[int]) -> np.ndarray:
        m = np.zeros(self.n, np.int8)
        m[list(idx)] = 1
        return m

    def frame(self, t: int, intent: Intent, subtask_instruction_idx: int) -> dict[str, np.ndarray]:
        """The annotation of frame ``t`` (the observation before the action of step ``t``)."""
        state = self.sim.state()
        cam = self.sim.head_camera()
        eef = self.sim.end_effector_poses()
        f = intent.focus
        seen = self.perception
        focus_visible = bool(f >= 0 and seen.visible[f])
        rec = {
            "subtask": intent.subtask,
            "stage": intent.stage,
            "subtask_instruction_idx": subtask_instruction_idx,
            "focus_object_idx": f,
            "focus_object_visible": int(focus_visible),
            "info_complete": int(intent.info_complete),
            "camera_mode": intent.camera_mode,
            "camera_target_theta": intent.camera_target_theta,
            "waist_heading_deg": 90.0 + math.degrees(state[TORSO_YAW]),
            "visible_object_mask": seen.visible.astype(np.int8),
            "discovered_object_mask": seen.discovered.astype(np.int8),
            "search_target_mask": self._mask(intent.search_targets),
            "action_target_mask": self._mask(intent.action_targets),
            "carried_object_mask": self._mask(intent.carried),
            "target_uv_norm": seen.uv[f] if focus_visible else np.array([-1.0, -1.0]),
            "object_uv_norm": np.where(seen.visible[:, None], seen.uv, -1.0),
            "intrinsic_cv": cam["intrinsic_cv"],
            "extrinsic_cv": cam["extrinsic_cv"],
            "cam2world_gl": cam["cam2world_gl"],
            "left_endpose": eef["left"],
            "right_endpose": eef["right"],
        }
        out = {}
        for k, (dtype, _) in FRAME_FIELDS.items():
            out[k] = np.asarray(rec[k], dtype=dtype)
        key = (intent.subtask, intent.stage, f)
        if key != self._last_key:
            self.transitions.append(
                {
                    "frame": t,
                    "subtask": intent.subtask,
                    "stage": int(intent.stage),
                    "stage_name": STAGE_NAMES[intent.stage],
                    "focus_object_idx": int(f),
                }
            )
            self._last_key = key
        return out
