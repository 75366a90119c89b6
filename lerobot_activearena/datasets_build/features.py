"""The dataset's feature set: LeRobot's standard keys plus every per-frame annotation of the paper's
schema as typed columns, padded to ``MAX_OBJECTS`` so all tasks share one feature set."""

from __future__ import annotations

import numpy as np

from ..annotations.schema import FRAME_FIELDS
from ..sim.action import ACTION_DIM, ACTION_NAMES
from ..sim.scene import CONTROL_HZ, HEAD_SIZE

FPS = CONTROL_HZ
MAX_OBJECTS = 16  # object-mask width; slots past a task's object count hold MASK_PAD
MASK_PAD = -1
IMAGE_KEY = "observation.images.head"
META_DIR = "meta/activearena"  # the build's own metadata inside the dataset root
KEYFRAME_COLUMNS = ("subtask_keyframe", "motion_keyframe", "chunk_keyframe")

# Paper field -> column name. Only ``subtask`` is renamed: LeRobot reserves ``subtask`` for text.
COLUMN_OF_FIELD = {name: name for name in FRAME_FIELDS} | {"subtask": "subtask_index"}
# NaN ("inactive") cannot go through LeRobot's aggregation (pandas turns it into a null the reader
# cannot load): such a field is stored as 0 with a 0/1 validity column beside it.
NAN_AS_FLAG = {"camera_target_theta": "camera_target_active"}
# What each column means (the dataset card's feature table); LeRobot's own columns are not listed.
COLUMN_DOCS = {
    IMAGE_KEY: "head-camera RGB, the observation before action t",
    "observation.state": "joint state, names as `action`",
    "action": "commanded absolute targets: left arm 7 + gripper, right arm 7 + gripper, torso yaw, head pitch",
    "subtask_index": "the paper's `subtask` (semantic subtask id)",
    "stage": "1 search, 2 anchor, 3 action",
    "subtask_instruction_idx": "index into the sidecar's subtask texts",
    "focus_object_idx": "object the expert attends to (-1 none)",
    "focus_object_visible": "1 when the focus object is visible",
    "info_complete": "1 once every fact the task needs has been seen",
    "camera_mode": "0 hold, 1 search, 2 center, 3 inspect",
    "camera_target_theta": "planned heading (deg) while the camera moves; 0 when inactive",
    "camera_target_active": "1 when `camera_target_theta` is meaningful (the paper's NaN = 0)",
    "waist_heading_deg": "90 + torso yaw (deg)",
    "visible_object_mask": "per task object: visible in this frame",
    "discovered_object_mask": "per task object: seen at some earlier or current frame",
    "search_target_mask": "per task object: the object being searched for",
    "action_target_mask": "per task object: the object being manipulated or used",
    "carried_object_mask": "per task object: held by a gripper",
    "target_uv_norm": "focus object's normalised image point, (-1, -1) when not visible",
    "object_uv_norm": "per task object: (u, v) as `target_uv_norm`, flattened; (-1, -1) when not visible",
    "intrinsic_cv": "3x3 camera intrinsics, row-major",
    "extrinsic_cv": "4x4 world-to-camera (OpenCV), row-major",
    "cam2world_gl": "4x4 camera-to-world (OpenGL), row-major",
    "left_endpose": "left TCP xyz + quaternion wxyz",
    "right_endpose": "right TCP xyz + quaternion wxyz",
    "subtask_keyframe": "1 at a subtask keyframe",
    "motion_keyframe": "1 at a motion keyframe",
    "chunk_keyframe": "1 at a chunk keyframe (t mod 16 == 0)",
}
# Matrices are stored flattened row-major (3x3 -> 9, 4x4 -> 16): LeRobot's aggregation, stats and
# viewers handle 1-D columns only. ``matrix(row, name)`` restores them.


def dataset_features(
    max_objects: int = MAX_OBJECTS, image_size: tuple[int, int] = HEAD_SIZE
) -> dict[str, dict]:
    """The dataset's features; ``image_size``: the head video's (height, width)."""
    feats: dict[str, dict] = {
        IMAGE_KEY: {
            "dtype": "video",
            "shape": (*image_size, 3),
            "names": ["height", "width", "channels"],
        },
        "observation.state": {"dtype": "float32", "shape": (ACTION_DIM,), "names": list(ACTION_NAMES)},
        "action": {"dtype": "float32", "shape": (ACTION_DIM,), "names": list(ACTION_NAMES)},
    }
    for name, (dtype, shape) in FRAME_FIELDS.items():
        shape = (int(np.prod([max_objects if s == "N" else s for s in shape])),)
        feats[COLUMN_OF_FIELD[name]] = {"dtype": np.dtype(dtype).name, "shape": shape, "names": None}
    for name in (*NAN_AS_FLAG.values(), *KEYFRAME_COLUMNS):
        feats[name] = {"dtype": "int8", "shape": (1,), "names": None}
    return feats


def frame_row(
    frame: dict,
    state: np.ndarray,
    action: np.ndarray,
    image: np.ndarray,
    keyframes: dict[str, int],
    instruction: str,
    features: dict[str, dict],
) -> dict:
    """One ``LeRobotDataset.add_frame`` dict from the expert's frame annotation."""
    row = {
        IMAGE_KEY: image,
        "observation.state": np.asarray(state, np.float32),
        "action": np.asarray(action, np.float32),
        "task": instruction,
    }
    for name, value in frame.items():
        col = COLUMN_OF_FIELD[name]
        ft = features[col]
        v = np.asarray(value, dtype=ft["dtype"]).reshape(-1)
        if name in NAN_AS_FLAG:
            active = np.isfinite(v).all()
            row[NAN_AS_FLAG[name]] = np.array([active], np.int8)
            v = v if active else np.zeros_like(v)
        if ft["shape"] != v.shape:  # an object mask: pad to the shared width
            n = v.shape[0]
            if n > ft["shape"][0]:
                raise ValueError(
                    f"{col} has {n} objects but the dataset holds at most {ft['shape'][0]}: "
                    f"raise datasets_build.features.MAX_OBJECTS"
                )
            v = np.concatenate([v, np.full(ft["shape"][0] - n, MASK_PAD, v.dtype)])
        row[col] = v
    for name in KEYFRAME_COLUMNS:
        row[name] = np.array([keyframes[name]], np.int8)
    return row


def matrix(row: dict, name: str):
    """The 3x3 / 4x4 camera matrix ``name`` of a dataset row (numpy array or torch tensor)."""
    shape = FRAME_FIELDS[name][1]
    return row[name].reshape(*row[name].shape[:-1], *shape)
