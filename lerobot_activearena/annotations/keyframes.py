"""History keyframes and memory views (paper App. "History-Keyframe Definitions" and the planner's
stride-16 input). Pure functions over per-frame arrays, shared by dataset building and policies.

Every event is *causal*: it is reported at the frame where it is confirmed, never earlier, so a
keyframe at t depends on the trajectory up to t only.
"""

from __future__ import annotations

import numpy as np

from ..sim.action import ACTION_NAMES, CONTROL_HZ

CHUNK = 16
STRIDE = 16

# Motion-keyframe constants (paper App. "History-Keyframe Definitions").
GRIPPER_CLOSED = 0.2  # normalised gripper <= 0.2: closed
GRIPPER_OPEN = 0.8  # >= 0.8: open
GRIPPER_CONFIRM = 2  # frames a gripper state must persist
ROTATION_RAD = 0.005  # |frame-to-frame change| above this: head pitch / torso yaw rotating
ROTATION_CONFIRM = 4  # consecutive rotating frames confirm an onset
ROTATION_MAX_GAP = 5  # still frames merged into one rotation; one more confirms its end
EEF_TURN_DEG = 40.0
EEF_STOP = 0.001  # m/s
MOTION_DEDUP = 5  # a candidate closer than this to the previous kept keyframe is dropped
FPS = CONTROL_HZ


def chunk_keyframes(length: int, chunk: int = CHUNK) -> np.ndarray:
    """k_t = 1[t mod C == 0] for t < T (T = ``length``)."""
    if length < 0 or chunk < 1:
        raise ValueError(f"need length >= 0 and chunk >= 1, got length={length}, chunk={chunk}")
    return (np.arange(length) % chunk == 0).astype(np.int8)


def subtask_keyframes(subtask) -> np.ndarray:
    """Frame 0 and the first frame after every change of the discrete subtask label."""
    s = np.asarray(subtask)
    k = np.zeros(len(s), np.int8)
    if len(s):
        k[0] = 1
        k[1:] = (s[1:] != s[:-1]).astype(np.int8)
    return k


def gripper_events(gripper) -> list[int]:
    """Frames where the gripper is confirmed to enter or leave a stable open / closed state
    (value classes closed / between / open; a class counts once it has held for 2 frames)."""
    g = np.asarray(gripper, float)
    cls = np.where(g <= GRIPPER_CLOSED, 0, np.where(g >= GRIPPER_OPEN, 2, 1))
    events, confirmed = [], (cls[0] if len(cls) else None)
    for t in range(GRIPPER_CONFIRM - 1, len(cls)):
        window = cls[t - GRIPPER_CONFIRM + 1 : t + 1]
        if (window == cls[t]).all() and cls[t] != confirmed:
            confirmed = cls[t]
            events.append(t)
    return events


def rotation_events(angle) -> list[int]:
    """Onset (4th consecutive frame with |delta| > 0.005 rad) and end (6th still frame after the
    last rotating one: interruptions of <= 5 frames are merged) of one joint's rotations."""
    q = np.asarray(angle, float)
    moving = np.zeros(len(q), bool)
    moving[1:] = np.abs(np.diff(q)) > ROTATION_RAD
    events, rotating, run, gap = [], False, 0, 0
    for t, m in enumerate(moving):
        if not rotating:
            run = run + 1 if m else 0
            if run == ROTATION_CONFIRM:
                events.append(t)
                rotating, gap = True, 0
        else:
            gap = 0 if m else gap + 1
            if gap > ROTATION_MAX_GAP:
                events.append(t)
                rotating, run = False, 0
    return events


def eef_events(positions, fps: int = FPS) -> list[int]:
    """End-effector turning (> 40 deg between consecutive velocities, both speeds > 0.001 m/s) and
    stopping (speed drops from > 0.001 to <= 0.001 m/s) events of one arm; positions (T, 3) in m."""
    p = np.asarray(positions, float)
    if len(p) < 3:
        return []
    v = np.diff(p, axis=0) * fps  # v[i] is the velocity at frame i + 1
    s = np.linalg.norm(v, axis=1)
    events = []
    for i in range(1, len(v)):
        prev, cur = s[i - 1], s[i]
        if prev > EEF_STOP and cur > EEF_STOP:
            cos = float(np.dot(v[i - 1], v[i]) / (prev * cur))
            if np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))) > EEF_TURN_DEG:
                events.append(i + 1)
        elif prev > EEF_STOP >= cur:
            events.append(i + 1)
    return events


def dedup(candidates, delta: int = MOTION_DEDUP) -> list[int]:
    """Chronological greedy de-duplication: keep a frame only if it is >= delta frames after the
    previously kept one."""
    kept: list[int] = []
    for t in sorted({int(c) for c in candidates}):
        if not kept or t - kept[-1] >= delta:
            kept.append(t)
    return kept


def motion_keyframes(states, eef_positions=None, delta: int = MOTION_DEDUP) -> np.ndarray:
    """k^mot over a trajectory of 18-D states (the paper's default events: both grippers and the
    head-pitch / torso-yaw rotations). ``eef_positions`` = {arm: (T, 3)} adds the optional
    end-effector turn / stop events."""
    x = np.asarray(states, float)
    length = len(x)
    k = np.zeros(length, np.int8)
    if length == 0:
        return k
    col = {n: i for i, n in enumerate(ACTION_NAMES)}
    events = [0]
    for name in ("left_gripper", "right_gripper"):
        events += gripper_events(x[:, col[name]])
    for name in ("torso_yaw", "head_pitch"):
        events += rotation_events(x[:, col[name]])
    for p in (eef_positions or {}).values():
        events += eef_events(p)
    k[dedup(events, delta)] = 1
    return k


def memory_view(t: int, keyframes, history: int = 12) -> list[int]:
    """M_t: the H = ``history`` most recent retained frames strictly before t (chronological)."""
    if history < 0:
        raise ValueError(f"history must be >= 0, got {history}")
    kept = np.flatnonzero(np.asarray(keyframes)[:t])
    return [int(i) for i in kept[len(kept) - history :]] if history else []


def stride_sequence(x: int, stride: int = STRIDE, history: int | None = None) -> list[int]:
    """S(x) = sort{x - j*s >= 0}; with ``history`` = K only the K + 1 most recent (x last)."""
    if x < 0:
        raise ValueError(f"frame index must be >= 0, got {x}")
    seq = list(range(x % stride, x + 1, stride))
    return seq if history is None else seq[-(history + 1) :]


def retrieval_positions(frames, subtask_keyframes, stride: int = STRIDE) -> list[int]:
    """Positions i of ``frames`` (chronological; the last is the current one) with q <= f_i < q + s
    for a subtask keyframe q observed by then (q <= the current frame); unique, chronological."""
    now = frames[-1]
    qs = [int(q) for q in subtask_keyframes if q <= now]
    return [i for i, f in enumerate(frames) if any(q <= f < q + stride for q in qs)]


def planned_memory(t: int, subtask_keyframes, stride: int = STRIDE) -> list[int]:
    """ActiveArena-Plan's executor memory before t: the frames of the uncapped S(t) inside a window
    [q, q + s) of a subtask keyframe q <= t (``subtask_keyframes``: frame indices), t excluded."""
    frames = stride_sequence(t, stride)
    return [frames[i] for i in retrieval_positions(frames, subtask_keyframes, stride) if frames[i] < t]


WRITE_POLICIES = ("chunk", "subtask", "motion", "planned", "none")


def memory_frames(policy: str, t: int, history: int = 12, keyframes=None) -> list[int]:
    """History frame indices (chronological, all < t) for a memory write policy, H = ``history``:
    ``chunk``: the stride-16 frames t-16H .. t-16 (at chunk boundaries these are the chunk keyframes);
    ``subtask`` / ``motion``: M_t over that keyframe indicator (``keyframes``, covering frames < t);
    ``planned``: the most recent H of ActiveArena-Plan's executor memory (``keyframes``: the subtask
    indicator, covering frames <= t); ``none``: no history."""
    if policy not in WRITE_POLICIES:
        raise ValueError(f"memory write policy must be one of {WRITE_POLICIES}, got {policy!r}")
    if policy == "none" or history == 0:
        return []
    if policy == "chunk":
        return stride_sequence(t, history=history)[:-1]
    if keyframes is None:
        kind = "subtask" if policy == "planned" else policy
        raise ValueError(f"the {policy!r} write policy needs the episode's {kind}_keyframe indicator")
    if policy == "planned":
        return planned_memory(t, np.flatnonzero(np.asarray(keyframes)[: t + 1]))[-history:]
    return memory_view(t, keyframes, history)
