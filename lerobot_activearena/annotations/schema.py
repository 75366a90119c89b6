"""The per-frame annotation schema (paper table "Per-frame trajectory fields") and its codes."""

from __future__ import annotations

import numpy as np

STAGE_SEARCH, STAGE_ANCHOR, STAGE_ACTION = 1, 2, 3
STAGE_NAMES = {STAGE_SEARCH: "search", STAGE_ANCHOR: "anchor", STAGE_ACTION: "action"}

# Active-camera state machine (camera_mode).
CAMERA_HOLD = 0  # head and torso hold their targets (arm actions, idle)
CAMERA_SEARCH = 1  # sweeping sectors for an object not yet seen
CAMERA_CENTER = 2  # turning to centre / face a located object
CAMERA_INSPECT = 3  # looking at a carried object to read hidden information
CAMERA_MODE_NAMES = {
    CAMERA_HOLD: "hold",
    CAMERA_SEARCH: "search",
    CAMERA_CENTER: "center",
    CAMERA_INSPECT: "inspect",
}

# field -> (numpy dtype, shape; "N" = number of registered task objects)
FRAME_FIELDS: dict[str, tuple[type, tuple]] = {
    "subtask": (np.int32, ()),
    "stage": (np.int8, ()),
    "subtask_instruction_idx": (np.int32, ()),
    "focus_object_idx": (np.int16, ()),
    "focus_object_visible": (np.int8, ()),
    "info_complete": (np.int8, ()),
    "camera_mode": (np.int8, ()),
    "camera_target_theta": (np.float32, ()),
    "waist_heading_deg": (np.float32, ()),
    "visible_object_mask": (np.int8, ("N",)),
    "discovered_object_mask": (np.int8, ("N",)),
    "search_target_mask": (np.int8, ("N",)),
    "action_target_mask": (np.int8, ("N",)),
    "carried_object_mask": (np.int8, ("N",)),
    "target_uv_norm": (np.float32, (2,)),
    # ours, beyond the paper's table: every task object's image point (the counted blocks' too)
    "object_uv_norm": (np.float32, ("N", 2)),
    "intrinsic_cv": (np.float32, (3, 3)),
    "extrinsic_cv": (np.float32, (4, 4)),
    "cam2world_gl": (np.float32, (4, 4)),
    "left_endpose": (np.float32, (7,)),
    "right_endpose": (np.float32, (7,)),
}
