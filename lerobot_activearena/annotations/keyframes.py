"""History keyframes and memory views (paper App. "History-Keyframe Definitions" and the planner's
stride-16 input). Pure functions over per-frame arrays, shared by dataset building and policies.

Motion keyframes (gripper / head-torso / end-effector events with de-duplication) are not here yet.
"""

from __future__ import annotations

import numpy as np

CHUNK = 16
STRIDE = 16


def chunk_keyframes(T: int, chunk: int = CHUNK) -> np.ndarray:
    """k_t = 1[t mod C == 0] for t < T."""
    if T < 0 or chunk < 1:
        raise ValueError(f"need T >= 0 and chunk >= 1, got T={T}, chunk={chunk}")
    return (np.arange(T) % chunk == 0).astype(np.int8)


def subtask_keyframes(subtask) -> np.ndarray:
    """Frame 0 and the first frame after every change of the discrete subtask label."""
    s = np.asarray(subtask)
    k = np.zeros(len(s), np.int8)
    if len(s):
        k[0] = 1
        k[1:] = (s[1:] != s[:-1]).astype(np.int8)
    return k


def memory_view(t: int, keyframes, H: int = 12) -> list[int]:
    """M_t: the H most recent retained frames strictly before t (chronological)."""
    if H < 0:
        raise ValueError(f"H must be >= 0, got {H}")
    kept = np.flatnonzero(np.asarray(keyframes)[:t])
    return [int(i) for i in kept[len(kept) - H:]] if H else []


def stride_sequence(x: int, stride: int = STRIDE, history: int | None = None) -> list[int]:
    """S(x) = sort{x - j*s >= 0}; with ``history`` = K only the K + 1 most recent (x last)."""
    if x < 0:
        raise ValueError(f"frame index must be >= 0, got {x}")
    seq = list(range(x % stride, x + 1, stride))
    return seq if history is None else seq[-(history + 1):]


def retrieval_positions(frames, subtask_keyframes_seen, stride: int = STRIDE) -> list[int]:
    """Positions i of ``frames`` with q <= f_i < q + s for some observed subtask keyframe q
    (unique, chronological)."""
    qs = list(subtask_keyframes_seen)
    return [i for i, f in enumerate(frames) if any(q <= f < q + stride for q in qs)]
