"""Training-time access to an ActiveArena dataset's annotations by global frame ``index``: the
current subtask text (for the ``<think>`` target) and the keyframe-memory frames (subtask / motion
write policies pick a per-sample set of past frames that LeRobot's fixed delta indices cannot express)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import torch

from ...annotations.keyframes import memory_frames
from .configuration_activearena_vla import IMAGE_KEY

# an object's place among 2 or 3 of its kind, by increasing azimuth (counter-clockwise: right to left)
PLACE_WORDS = {2: ("right", "left"), 3: ("right", "middle", "left")}


def decided_kin(placements: list[dict], decision: str) -> tuple[str, list[str]]:
    """The object a decision ends on ("place on the blue pad": blue_pad), and the names of its category's
    objects by increasing azimuth (a scene's or a sidecar's ``placements``)."""
    name = "_".join(decision.split()[-2:])
    found = [p for p in placements if p["name"] == name]
    if not found:
        raise ValueError(
            f"the decision {decision!r} names {name}, which is not among the scene's placements: "
            "--policy.decision_place needs decisions that end on a placed object's name"
        )
    kin = [
        n
        for _, n in sorted(
            (p["angle"], p["name"]) for p in placements if p["category"] == found[0]["category"]
        )
    ]
    if len(kin) not in PLACE_WORDS:
        raise ValueError(f"--policy.decision_place names one of two or three objects, {name} has {len(kin)}")
    return name, kin


def place_word(placements: list[dict], decision: str) -> str:
    """Where the object a decision ends on lies among the objects of its category, by azimuth: right /
    middle / left of three, right / left of two."""
    name, kin = decided_kin(placements, decision)
    return PLACE_WORDS[len(kin)][kin.index(name)]


def where(placements: list[dict], name: str) -> str:
    """Where a placed object lies from the robot's base, as a span writes it: "at 40 cm, 54 deg" (the
    scene's polar placement rounded to a centimetre and a degree; 90 deg is straight ahead)."""
    found = [p for p in placements if p["name"] == name]
    if not found:
        raise ValueError(
            f"{name} is not among the scene's placements ({[p['name'] for p in placements]}): "
            "--policy.decision_where names where the object acted on lies, from the placements the "
            "episode's sidecar records"
        )
    return f"at {round(100 * found[0]['r'])} cm, {round(found[0]['angle'])} deg"


# what ``where`` writes, and the object named before it ("gray block at 40 cm", "red pad, the left one at 37 cm")
WHERE_TEXT = re.compile(r"(\w+) (\w+)(?:, the \w+ one)? at (\d+) cm, (\d+) deg")
WHERE_TAIL = re.compile(r" at \d+ cm, \d+ deg$")  # the ``where`` a span ends with


def read_where(text: str) -> tuple[str, int, int] | None:
    """The object a ``decision_where`` span places and where: (name, cm, deg), or None without a place."""
    m = WHERE_TEXT.search(text)
    return (f"{m.group(1)}_{m.group(2)}", int(m.group(3)), int(m.group(4))) if m else None


def pick_clause(placements: list[dict], name: str) -> str:
    """The ``decision_where`` clause of the frames that pick the inspected object: "gray block at 40 cm,
    54 deg"."""
    return f"{name.replace('_', ' ')} {where(placements, name)}"


def decision_clause(
    placements: list[dict], decision: str, place: bool = False, layout: bool = False, where_: bool = False
) -> str:
    """A decision as the ``think=decision`` target writes it after the subtask. With ``place``, its object
    is also named by its place among the objects of its kind, as the robot sees them by azimuth ("place
    on the blue pad, the right one"); with ``layout`` it follows the places of all of them ("blue pad
    right, green pad middle, red pad left; ..."); with ``where_`` it ends with where that object lies
    ("... at 36 cm, 26 deg")."""
    if not (place or layout or where_):
        return decision
    name, kin = decided_kin(placements, decision)
    text = f"{decision}, the {PLACE_WORDS[len(kin)][kin.index(name)]} one" if place else decision
    if where_:
        text = f"{text} {where(placements, name)}"
    if layout:
        listed = zip(kin, PLACE_WORDS[len(kin)], strict=True)
        text = ", ".join(f"{n.replace('_', ' ')} {w}" for n, w in listed) + f"; {text}"
    return text


COLUMNS = ("episode_index", "frame_index", "subtask_index", "subtask_keyframe", "motion_keyframe")


class DatasetAnnotations:
    def __init__(self, root: str | Path, repo_id: str = "local/activearena"):
        from lerobot.datasets.lerobot_dataset import LeRobotDataset

        root = Path(root)
        if not (root / "meta/info.json").is_file():
            raise FileNotFoundError(
                f"{root} is not a LeRobot dataset (no meta/info.json); set --policy.dataset_root "
                "to the ActiveArena dataset used for training"
            )
        self.ds = LeRobotDataset(repo_id, root=root, video_backend="pyav")
        missing = [c for c in COLUMNS if c not in self.ds.features]
        if missing:
            raise ValueError(
                f"{root} lacks the ActiveArena annotation columns {missing}: train on the dataset "
                "activearena-build-dataset wrote, or on a copy made with activearena-slim-dataset --vla"
            )
        table = self.ds.hf_dataset.with_format("numpy").select_columns(list(COLUMNS))[:]
        self.cols = {c: np.asarray(table[c]).reshape(-1) for c in COLUMNS}
        self.ep_start = {int(e["episode_index"]): int(e["dataset_from_index"]) for e in self.ds.meta.episodes}
        self.ep_end = {int(e["episode_index"]): int(e["dataset_to_index"]) for e in self.ds.meta.episodes}
        self.subtask_text: dict[int, dict[int, str]] = {}
        self.instruction: dict[int, str] = {}
        self.decisions: dict[int, list[tuple[int, str]]] = {}  # (frame read on, decision), in order
        self.inspected: dict[int, str | None] = {}  # the object the expert first inspected
        # frames [from, to) of a grasp-retry build's missed tries (expert_notes.grasp_misses)
        self.misses: dict[int, list[tuple[int, int]]] = {}
        # the scene's objects on the table (name, category, angle)
        self.placements: dict[int, list[dict]] = {}
        for ep in self.ep_start:
            side = json.loads((root / f"meta/activearena/sidecars/episode_{ep:06d}.json").read_text())
            self.subtask_text[ep] = {int(s["id"]): s["text"] for s in side["subtasks"]}
            self.instruction[ep] = side["instruction"]
            self.placements[ep] = side.get("placements", [])
            inspections = (side.get("expert_notes") or {}).get("inspections", [])
            self.decisions[ep] = sorted(
                (int(e["frame"]), e["decision"]) for e in inspections if e.get("decision")
            )
            self.inspected[ep] = inspections[0].get("object") if inspections else None
            misses = (side.get("expert_notes") or {}).get("grasp_misses", [])
            self.misses[ep] = [(int(a), int(b)) for a, b in misses]

    def decision_onsets(self, window: int) -> np.ndarray:
        """Per global frame: whether it is among the first ``window`` frames of a subtask that began at
        or after the episode's first reading (where the expert starts acting on what it read)."""
        ep, sub = self.cols["episode_index"], self.cols["subtask_index"]
        new_subtask = np.ones(len(ep), dtype=bool)
        new_subtask[1:] = (ep[1:] != ep[:-1]) | (sub[1:] != sub[:-1])
        starts = np.flatnonzero(new_subtask)
        start_of = starts[np.searchsorted(starts, np.arange(len(ep)), side="right") - 1]
        frame = self.cols["frame_index"]
        first_reading = np.array(
            [self.decisions[int(e)][0][0] if self.decisions[int(e)] else np.inf for e in ep], dtype=float
        )
        return (frame[start_of] >= first_reading) & (np.arange(len(ep)) - start_of < window)

    def miss_frames(self) -> np.ndarray:
        """Per global frame: whether it lies in a missed try of a grasp-retry build (``--grasp-miss``:
        the arm ran off the recorded command, then holds while it comes back)."""
        out = np.zeros(len(self.cols["episode_index"]), dtype=bool)
        for e, spans in self.misses.items():
            for a, b in spans:  # episode frames -> global indices, within the episode
                out[self.ep_start[e] + a : min(self.ep_start[e] + b, self.ep_end[e])] = True
        return out

    def subtask(self, index: int) -> str:
        ep, sid = int(self.cols["episode_index"][index]), int(self.cols["subtask_index"][index])
        return self.subtask_text[ep].get(sid, self.instruction[ep])

    def decision(self, index: int) -> str | None:
        """The decision the expert took from the last hidden face it read at or before the frame at
        global ``index`` (``expert_notes.inspections``), or None before any reading."""
        ep, x = int(self.cols["episode_index"][index]), int(self.cols["frame_index"][index])
        made = [d for frame, d in self.decisions[ep] if frame <= x]
        return made[-1] if made else None

    def subtask_and_decision(
        self, index: int, place: bool = False, layout: bool = False, where_: bool = False
    ) -> str:
        """The subtask text, with the decision in force appended (``decision_clause``): the
        ``think=decision`` target. With ``where_``, the frames of the episode's first subtask (the pick)
        before any reading name where the inspected object lies ("...; gray block at 40 cm, 54 deg"),
        and the decision ends with where its object lies."""
        decision = self.decision(index)
        ep = int(self.cols["episode_index"][index])
        if decision is None:
            first = min(self.subtask_text[ep], default=None)
            if where_ and self.inspected[ep] and int(self.cols["subtask_index"][index]) == first:
                return f"{self.subtask(index)}; {pick_clause(self.placements[ep], self.inspected[ep])}"
            return self.subtask(index)
        return (
            f"{self.subtask(index)}; {decision_clause(self.placements[ep], decision, place, layout, where_)}"
        )

    def place_of(self, ep: int, decision: str) -> str:
        """Where the object a decision ends on lies among the objects of its category (``place_word``)."""
        return place_word(self.placements[ep], decision)

    def subtask_keyframes(self, index: int) -> tuple[int, list[int]]:
        """The frame at global ``index``'s episode position x and its episode's subtask keyframes <= x."""
        ep = int(self.cols["episode_index"][index])
        start = self.ep_start[ep]
        x = index - start
        return x, [int(q) for q in np.flatnonzero(self.cols["subtask_keyframe"][start : index + 1])]

    def memory_indices(self, index: int, policy: str, history: int) -> list[int]:
        """Global indices of M_t for the frame at global ``index`` (chronological, all before it)."""
        ep = int(self.cols["episode_index"][index])
        start = self.ep_start[ep]
        kind = "subtask" if policy == "planned" else policy  # the executor's windows: subtask keyframes
        kf = (
            self.cols[f"{kind}_keyframe"][start : self.ep_end[ep]]
            if policy in ("subtask", "motion", "planned")
            else None
        )
        return [start + f for f in memory_frames(policy, index - start, history, kf)]

    def memory_batch(
        self,
        index: torch.Tensor,
        current: torch.Tensor,
        state: torch.Tensor | None,
        policy: str,
        history: int,
    ) -> tuple[torch.Tensor, torch.Tensor | None, torch.Tensor]:
        """(B, history+1, C, H, W) images, (B, history+1, D) states and (B, history+1) is_pad: the memory
        frames left-padded, then the current frame."""
        batch_size = current.shape[0]
        images = current.new_zeros((batch_size, history + 1, *current.shape[1:]))
        states = None if state is None else state.new_zeros((batch_size, history + 1, state.shape[-1]))
        pad = torch.ones(batch_size, history + 1, dtype=torch.bool)
        for b in range(batch_size):
            mem = self.memory_indices(int(index[b]), policy, history)
            slots = range(history - len(mem), history)
            for slot, g in zip(slots, mem, strict=True):
                item = self.ds[g]
                images[b, slot] = item[IMAGE_KEY].to(current)
                if states is not None:
                    states[b, slot] = item["observation.state"].to(state)
                pad[b, slot] = False
            images[b, history] = current[b]
            if states is not None:
                states[b, history] = state[b]
            pad[b, history] = False
        return images, states, pad

    def memory_index_batch(
        self, index: torch.Tensor, state: torch.Tensor | None, history: int
    ) -> tuple[torch.Tensor, torch.Tensor | None]:
        """The chunk memory by index (for a vision cache): (B, history) global indices of the memory frames,
        left-padded with -1, and (B, history+1, D) states (the memory frames' from the dataset, zeros where
        padded, then the current one), or None without a state."""
        batch_size = len(index)
        rows = torch.full((batch_size, history), -1, dtype=torch.long)
        states = None if state is None else state.new_zeros((batch_size, history + 1, state.shape[-1]))
        for b in range(batch_size):
            mem = self.memory_indices(int(index[b]), "chunk", history)
            if mem:
                rows[b, history - len(mem) :] = torch.tensor(mem)
                if states is not None:
                    states[b, history - len(mem) : history] = torch.from_numpy(self.states[mem]).to(state)
            if states is not None:
                states[b, history] = state[b]
        return rows, states

    @property
    def states(self) -> np.ndarray:
        """Every frame's ``observation.state``, (N, D) by global index (loaded at first use)."""
        if not hasattr(self, "_states"):
            column = self.ds.hf_dataset.with_format("numpy").select_columns(["observation.state"])[:]
            self._states = np.stack(column["observation.state"]).astype(np.float32)
        return self._states
