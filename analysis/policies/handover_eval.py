"""Which part of a task a policy fails at: the scripted expert plays each episode up to a handover
point, then the policy finishes it (``lerobot_activearena.eval.handover``; the policy sees every
observation from the first step, so its memory bank holds what the expert's views put there).

    python analysis/policies/handover_eval.py CHECKPOINT --task count_target_press_button \\
        --episode-indices 50-59 --handover start,subtask:2,subtask:2+12

Handover points: ``start`` (the policy alone, as ``activearena-eval`` plays it), ``never`` (the
expert alone: a check of the harness), ``subtask:K`` (the first frame the expert's own episode
annotates with subtask K, e.g. the count task's press once the blocks are counted), ``subtask:K+N``
(N frames later). Validation episodes (manifest ID 50 on) by default; ``--scene-seeds 0-19`` plays a
training build's own scenes instead. Prints, per handover point, the successes and failure states
(DM / CO / CR), and on an inspect-and-place task what the object rests on at the end: the
destination its reading names, another support, or none (of those on none: how many a gripper still
holds, how far the others end from the named destination), how far round from the named
destination it was let go, and the policy's reach from the handover on (does the hand's nearest point
to the object follow its distance from the base and its angle round the fan, as ``pick_offsets.py``).
Hand over where the expert has turned to the object and not yet moved an arm (check_block_color:
``subtask:1+6 --replan``) to see whether the policy reaches to the object from the expert's view.
``--replan``: the policy decides at the handover; without it a handover between the policy's
decisions (every 16 steps) first plays the rest of the chunk it decided before the handover (at
``subtask:1+6``, the chunk of step 0, from the home view).

Does a policy place by what its memory holds? Hand over where placing starts (check_block_color:
``subtask:4``, the block picked, its patch shown and turned away again) with the memory as it is
and with ``--memory-ablation blank`` or ``drop`` (the memory frames gray, or left out as at the
episode's first step, from the handover on; before it the policy's actions are discarded anyway): a
policy that reads the colour from memory puts the block on the named pad with its memory and on any
pad without it.

Is it the decision or the set-down that fails? A think-first ``think=decision`` policy (its actions
read the span it decodes) can be played with ``--span true``: at every decision the span it decoded
keeps its subtask, and the rest is replaced by what the scene's reading gives (the layout and the
decision with its place, as its training targets write them). The decision is then right by
construction; what fails is the acting on it. Use it with a handover after the reading: before it the
forced decision also lands in the spans of the subtasks before the reading, which training never shows.
With ``decision_where`` a span that names the pick subtask is forced to where the object lies instead,
so a handover at ``start`` tests whether the reach follows the place the span gives (read it for the
pick only). Every run prints how often the decoded span named the right decision at the decisions
after the handover and, with ``decision_where``, how far the place it gave was off, per object, and
of the episodes that lifted the object, in how many the span last named the destination and how many
of those set it down there (a wrong choice against a missed set-down), and of the episodes where a
gripper shut on nothing, in how many it shut again after (a retry) and lifted.
``--span-from READER``: the policy acts on the decision another think-first checkpoint decodes from the
same observations (READER sees every step, decides at the same steps; the policy's own subtask is
kept): one checkpoint's reading with another's hand, e.g. how far a memory run's reading carried by
the memory-free run's set-down would go. The decisions reported are READER's; the records also count
how often the policy's own span was right.
``--video DIR`` writes each episode's head camera with the step, who acts and the span's decision.
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import importlib.util
import json
from collections import Counter
from pathlib import Path

import numpy as np

from lerobot_activearena.cli.args import int_ranges
from lerobot_activearena.eval.handover import handover_step, play_with_handover, torso_offset
from lerobot_activearena.policies.activearena_vla.dataset_annotations import (
    WHERE_TAIL,
    decision_clause,
    pick_clause,
    read_where,
)
from lerobot_activearena.sim.action import GRIPPER_INDICES, TORSO_YAW
from lerobot_activearena.sim.embodiment import ARMS, TCP_SITES
from lerobot_activearena.tasks import predicates
from lerobot_activearena.tasks.shapes.inspection import InspectAndPlaceTask


def checkpoint_label(path) -> str:
    """``RUN/STEP`` for a lerobot-train checkpoint (``.../RUN/checkpoints/STEP/pretrained_model``),
    else the path as given: what the records name the policy by."""
    parts = Path(path).resolve().parts
    if len(parts) >= 4 and parts[-1] == "pretrained_model" and parts[-3] == "checkpoints":
        return f"{parts[-4]}/{parts[-2]}"
    return str(path)


def _sibling(name: str):
    spec = importlib.util.spec_from_file_location(name, Path(__file__).with_name(f"{name}.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


pick_offsets = _sibling("pick_offsets")


def where_it_rests(env) -> dict:
    """On an inspect-and-place task's env after an episode: the support its inspected object rests on
    (None: none) and the destination the object's reading names."""
    task, scene = env.spec_task, env.scene
    obj = scene.obj(task.inspected[0])
    return {
        "rests_on": pick_offsets.resting_support(env.sim, scene, obj),
        "destination": task.read(scene, obj.attributes).destination,
        "held": pick_offsets.held(env.sim, obj),
        "offsets": pick_offsets.support_offsets(env.sim, scene, obj),
        "tilt_deg": float(np.degrees(np.arccos(np.clip(env.sim.data.body(obj.body).xmat[8], -1.0, 1.0)))),
    }


class ReleaseWatch:
    """A ``render_callback``: where (polar: m, deg) the inspected object was when a gripper last let
    go of it, which way the torso faced then (deg, the same polar frame: 90 is the home heading), and
    where the destination its reading names is."""

    def __init__(self, env):
        self.env, self.held, self.released_at, self.heading_at_release = env, False, None, None

    def __call__(self, vec) -> None:
        sim, obj = self.env.sim, self.env.scene.obj(self.env.spec_task.inspected[0])
        held = pick_offsets.held(sim, obj)
        if self.held and not held:
            self.released_at = predicates.polar(sim.data.body(obj.body).xpos[:2])
            self.heading_at_release = 90.0 + float(np.degrees(sim.state()[TORSO_YAW]))
        self.held = held

    def row(self) -> dict:
        scene = self.env.scene
        obj = scene.obj(self.env.spec_task.inspected[0])
        dest = scene.obj(self.env.spec_task.read(scene, obj.attributes).destination)
        return {
            "released_at": self.released_at,
            "heading_at_release": self.heading_at_release,
            "destination_at": predicates.polar(self.env.sim.data.body(dest.body).xpos[:2]),
        }


def where_error(text: str, placements: list[dict]) -> tuple[str, float, float] | None:
    """How far the place a ``decision_where`` span gives ("gray block at 40 cm, 54 deg") is from where the
    object it names lies: (its name, |cm|, |deg|), or None where the span gives no place of a placed
    object."""
    given = read_where(text)
    found = [p for p in placements if given and p["name"] == given[0]]
    if not found:
        return None
    return found[0]["name"], abs(given[1] - 100 * found[0]["r"]), abs(given[2] - found[0]["angle"])


class ReachWatch:
    """A ``render_callback``: the policy's pick of the inspected object from the handover on (the
    nearest either tool centre came to it, where, and how far the pick got), as ``pick_offsets.py``
    records it for a whole episode; and the torso's heading against the expert's own episode
    (``expert_states``) at the end of the policy's first chunk (``chunk`` steps after the handover)
    and where the hand came nearest, with the hand's angle round from the heading there."""

    def __init__(self, env, handover: int, expert_states, chunk: int):
        self.env, self.handover, self.t, self.record = env, handover, 0, None
        self.expert, self.chunk, self.headings = expert_states, chunk, {}
        self.shut, self.closes, self.closing = None, [], {}  # closes: each one on nothing or not

    def _grippers(self, state, away: list[float]) -> None:
        """Each time a gripper shuts after the handover: did it shut on nothing (``GRIP_EMPTY``), and how
        far (cm) its tool centre was from the object then (``away``: per arm, in ``ARMS`` order)."""
        grip = np.asarray(state)[list(GRIPPER_INDICES)]
        shut = grip < GRIP_SHUT
        for k, now in enumerate(shut):
            if self.shut is not None and now and not self.shut[k]:
                self.closing[k] = len(self.closes)
                self.closes.append([False, round(100 * away[k], 1)])
            if now and k in self.closing and grip[k] < GRIP_EMPTY:
                self.closes[self.closing[k]][0] = True
        self.shut = shut

    def _heading_off(self, t: int, yaw: float) -> float | None:
        return float(np.degrees(yaw - self.expert[t][TORSO_YAW])) if t < len(self.expert) else None

    def __call__(self, vec) -> None:
        t, self.t = self.t, self.t + 1  # the first call follows the reset: frame t's state
        if t < self.handover:
            return
        sim, obj = self.env.sim, self.env.scene.obj(self.env.spec_task.inspected[0])
        centre, yaw = predicates.centre_point(sim, obj), float(sim.state()[TORSO_YAW])
        tcp = {arm: sim.data.site(TCP_SITES[arm]).xpos.copy() for arm in ARMS}
        self._grippers(sim.state(), [float(np.linalg.norm(tcp[arm] - centre)) for arm in ARMS])
        if self.record is None:
            self.record = pick_offsets.new_record(centre[:2])
        before = min(self.record["nearest"].values())
        pick_offsets.update(
            self.record,
            tcp,
            centre,
            {arm: predicates.grasped_by(sim, obj.body, arm) for arm in ARMS},
            float(sim.data.body(obj.body).xpos[2] - sim.model.body(obj.body).pos[2]),
        )
        if t == self.handover + self.chunk:
            self.headings["heading_off_after_first_chunk_deg"] = self._heading_off(t, yaw)
        arm = min(ARMS, key=self.record["nearest"].get)
        if self.record["nearest"][arm] < before:  # the hand came nearer than ever: where, and the heading
            self.headings["heading_off_at_nearest_deg"] = self._heading_off(t, yaw)
            hand = self.record["nearest_xy"][arm]
            self.headings["hand_from_heading_deg"] = predicates.polar(hand)[1] - np.degrees(yaw)

    def row(self) -> dict:
        if self.record is None:
            return {}
        s = pick_offsets.summary(self.record)
        return {
            "reach_nearest_cm": 100 * s["nearest"],
            "reach_stage": s["stage"],
            "object_start_xy": s["start_xy"].tolist(),
            "hand_nearest_xy": s["nearest_xy"].tolist(),
            "shuts": self.closes,
        } | self.headings


GRIP_SHUT = 0.7  # a gripper's state below this has shut (open: 1)
GRIP_EMPTY = 0.15  # ... below this it shut on nothing (on the block it stops near 0.4)
RETRY_NEAR_CM = 6.0  # a shut after one on nothing with the tool centre this near the object: a retry


def retry_line(rows: list[dict]) -> str:
    """Of the episodes where a gripper shut on nothing: in how many one shut again near the object
    after that (a retry), and how many of those lifted it."""
    missed = [r for r in rows if any(empty for empty, _ in r.get("shuts", []))]
    if not missed:
        return ""
    retried = []
    for r in missed:
        first = [empty for empty, _ in r["shuts"]].index(True)
        if any(cm < RETRY_NEAR_CM for _, cm in r["shuts"][first + 1 :]):
            retried.append(r)
    lifted = sum(r["reach_stage"] == "lift" for r in retried)
    return (
        f"    a gripper shut on nothing in {len(missed)}; in {len(retried)} of those one shut again within "
        f"{RETRY_NEAR_CM:.0f} cm of the object, {lifted} of which lifted it"
    )


TURN_TOLERANCE_DEG = float(np.degrees(0.12))  # the demonstrations' largest off-centre turn (--face-jitter)


def reach_line(rows: list[dict]) -> str:
    """The policy's reach over episodes (``pick_offsets.reach_tracking``) and how far its picks got."""
    mine = [r for r in rows if "hand_nearest_xy" in r]
    if len(mine) < 3:
        return ""
    summaries = [
        {"start_xy": np.array(r["object_start_xy"]), "nearest_xy": np.array(r["hand_nearest_xy"])}
        for r in mine
    ]
    t = pick_offsets.reach_tracking(summaries)
    stages = Counter(r["reach_stage"] for r in mine)
    text = (
        f"    reach from the handover: distance / angle correlation {t['radius_corr']:.2f} / "
        f"{t['angle_corr']:.2f}, median miss {100 * t['median_miss_m']:.1f} cm (objects "
        f"{100 * t['median_from_mean_m']:.1f} cm from their mean); furthest stage {dict(stages)}"
    )
    off = [r.get("heading_off_after_first_chunk_deg") for r in mine]
    off = np.abs([o for o in off if o is not None])
    if len(off):
        far = [r for r in mine if abs(r.get("heading_off_at_nearest_deg") or 0.0) > TURN_TOLERANCE_DEG]
        text += (
            f"\n    torso heading after the policy's first chunk: {np.median(off):.1f} deg from the expert's "
            f"(median), over {TURN_TOLERANCE_DEG:.1f} in {int((off > TURN_TOLERANCE_DEG).sum())} of {len(off)}; "
            f"{len(far)} still that far off where the hand came nearest, "
            f"missing by {np.median([r['reach_nearest_cm'] for r in far]) if far else float('nan'):.1f} cm (median)"
        )
    return text


def decodes_decision_first(policy) -> bool:
    """A think-first ``think=decision`` policy: its actions read the span it decodes first."""
    return policy.config.think == "decision" and getattr(policy, "think_first", False)


class SpanWatch:
    """Wraps a think-first policy's ``greedy_decode``: records, per decision, the env step, whether the
    decoded span's text after its subtask is the scene's true one and (``decision_where``) how far the
    place it gives is from the object it names; with ``force`` it returns that true text instead (the
    decoded subtask kept). With ``decision_where`` the true text of a span that names the task's first
    subtask (the pick) is where the inspected object lies, as training writes it."""

    def __init__(self, policy, env, force: bool, source: SpanWatch | None = None):
        self.policy, self.env, self.force, self.decisions, self.last = policy, env, force, [], ""
        self.source, self.unmatched = source, 0  # force the source's decoded decision, not the truth
        self.decided, self.decided_at = "", -1  # the last decoded decision and its env step
        self.decode, self.tokenizer = policy.greedy_decode, policy.text_tokenizer
        self.start, self.end = policy.think_token_ids()
        self.wheres: list[tuple[int, tuple[str, float, float]]] = []
        policy.greedy_decode = self

    def truth(self, subtask: str = "") -> str:
        task, scene = self.env.spec_task, self.env.scene
        placements, cfg = scene.params["placements"], self.policy.config
        if cfg.decision_where and subtask.strip() == task.subtasks[0].text:
            return pick_clause(placements, task.inspected[0])
        reading = task.read(scene, scene.obj(task.inspected[0]).attributes)
        return decision_clause(
            placements, reading.text, cfg.decision_place, cfg.decision_layout, cfg.decision_where
        )

    def __call__(self, encode_args, start, stop, *args, **kwargs):
        tokens, logits, first = self.decode(encode_args, start, stop, *args, **kwargs)
        if start != [self.start]:
            return tokens, logits, first
        out = []
        for t in tokens:
            text = self.tokenizer.decode([i for i in t if i != self.end])
            subtask, _, decided = text.partition("; ")
            truth = self.truth(subtask)
            # the decision is right where it names the true text; the place it gives is scored apart
            self.decisions.append(
                (self.policy.step, WHERE_TAIL.sub("", decided.strip()) == WHERE_TAIL.sub("", truth))
            )
            off = where_error(decided, self.env.scene.params["placements"])
            if off is not None:
                self.wheres.append((self.policy.step, off))
            if self.source is not None:
                # the reader decoded on this step's observation first (SpanReader); else its last span
                self.unmatched += self.source.decided_at != self.policy.step
                truth = self.source.decided
            self.last = decided.strip() if not self.force else f"{decided.strip()} -> forced: {truth}"
            self.decided, self.decided_at = decided.strip(), self.policy.step
            if self.force:
                forced = self.tokenizer(f"{subtask}; {truth}", add_special_tokens=False)["input_ids"]
                t = (*forced, self.end)
            out.append(tuple(t))
        return out, logits, first

    def right_after(self, step: int) -> tuple[int, int]:
        """(decoded right, decisions) among those at or after env step ``step``; then forgets them."""
        after = [right for t, right in self.decisions if t >= step]
        self.decisions, self.last = [], ""
        return sum(after), len(after)

    def where_after(self, step: int) -> list[tuple[int, str, float, float]]:
        """The decoded places' (env step, object, |cm|, |deg|) errors at or after env step ``step``; then
        forgets them."""
        after = [(t, *off) for t, off in self.wheres if t >= step]
        self.wheres = []
        return after


class SpanReader:
    """``--span-from``: the acting policy's preprocessor wrapped so that every observation also goes,
    first, to a second (reader) policy through its own preprocessor; the reader's actions are
    discarded, its decoded span kept (its ``SpanWatch``). The reader's bank fills from the same views
    and it decodes at the same steps (same ``n_action_steps``), so at each of the actor's decisions the
    reader's span of that observation is there to force."""

    def __init__(self, actor, pre, reader, reader_pre):
        self.pre, self.reader, self.reader_pre = pre, reader, reader_pre
        if reader.config.n_action_steps != actor.config.n_action_steps:
            raise ValueError(
                f"--span-from: the reader decides every {reader.config.n_action_steps} steps, the policy every "
                f"{actor.config.n_action_steps}; pass --n-action-steps so both decide at the same steps"
            )
        real_reset, real_replan = actor.reset, actor.replan
        actor.reset = lambda: (reader.reset(), real_reset())[-1]
        actor.replan = lambda: (reader.replan(), real_replan())[-1]

    def __call__(self, observation):
        self.reader.select_action(self.reader_pre(copy.deepcopy(observation)))
        return self.pre(observation)


class VideoWatch:
    """A ``render_callback`` writing the head camera to ``path``, each frame captioned with its step,
    who acts (expert before ``handover``, then the policy) and the last decoded span's decision."""

    def __init__(self, env, path: Path, handover: int, spans: SpanWatch | None):
        from lerobot_activearena.sim.video import Mp4Writer

        self.env, self.handover, self.spans, self.t = env, handover, spans, 0
        self.writer = Mp4Writer(path)

    def __call__(self, vec) -> None:
        from lerobot_activearena.sim.video import draw_annotations

        lines = [f"step {self.t} {'expert' if self.t < self.handover else 'policy'}"]
        if self.spans is not None and self.spans.last:
            lines += [part.strip() for part in self.spans.last.replace(" -> ", ";").split(";")]
        self.writer.write(draw_annotations(self.env.render(), lines, []))
        self.t += 1


def release_angles(rows: list[dict]) -> str:
    """How far round from the named destination the object was let go (median |angle difference|)."""
    let_go = [r for r in rows if r["released_at"]]
    if not let_go:
        return "; never let go"
    off = [abs(r["released_at"][1] - r["destination_at"][1]) for r in let_go]
    text = f"; let go {np.median(off):.0f} deg round from the named one (median of {len(off)})"
    named = [r["destination_at"][1] for r in let_go]
    if len(let_go) > 2 and np.ptp(named) > 0:
        released = np.corrcoef([r["released_at"][1] for r in let_go], named)[0, 1]
        heading = np.corrcoef([r["heading_at_release"] for r in let_go], named)[0, 1]
        text += (
            f", correlation with the named one's angle: release {released:.2f}, torso heading {heading:.2f}"
        )
    return text


def missed_places(rows: list[dict]) -> str:
    """Of the episodes whose object rests on no support: how many a gripper still holds, and how far
    the others' centres end from the named destination (median, cm)."""
    missed = [r for r in rows if r["rests_on"] is None]
    if not missed:
        return ""
    held = sum(r["held"] for r in missed)
    off = [100 * r["offsets"][r["destination"]] for r in missed if not r["held"]]
    text = f"; of the {len(missed)} on no support {held} still held"
    if off:
        text += (
            f", the others {np.median(off):.1f} cm from the named one (median; {min(off):.1f}-{max(off):.1f})"
        )
    return text


def lifted_choices(rows: list[dict]) -> str:
    """Of the episodes that lifted the object: in how many the span's last named support was the
    destination (the decision), and how many of those set the object on it (the place)."""
    lifted = [r for r in rows if r.get("reach_stage") == "lift"]
    if not lifted or not any(r.get("span_where_errors") for r in lifted):
        return ""
    right = []
    for r in lifted:
        named = [w[1] for w in r.get("span_where_errors", []) if w[1] in r["offsets"]]
        if named and named[-1] == r["destination"]:
            right.append(r)
    placed = sum(r["rests_on"] == r["destination"] for r in right)
    return (
        f"    of the {len(lifted)} that lifted, the span last named the destination in {len(right)}, "
        f"{placed} of those set down on it"
    )


def end_place(row: dict) -> str:
    if row["rests_on"] is None:
        return "no support"
    return "the named one" if row["rests_on"] == row["destination"] else "another support"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("checkpoint", type=Path, help="an ActiveArena-VLA pretrained_model folder")
    p.add_argument("--task", required=True)
    p.add_argument("--split", default="id")
    p.add_argument("--episode-indices", default="50-59", help="manifest indices (default: validation)")
    p.add_argument(
        "--scene-seeds",
        help="scene seeds played as given instead of manifest episodes, e.g. a training build's 0-19: "
        "does the policy do on the scenes it was trained on what it fails on held-out ones",
    )
    p.add_argument("--handover", default="start,subtask:2", help="comma-separated handover points")
    p.add_argument(
        "--memory-ablation",
        choices=("none", "blank", "drop"),
        default="none",
        help="blank: the policy's memory frames gray; drop: its memory slots empty, as at an episode's "
        "first step (as --policy.memory_ablation)",
    )
    p.add_argument(
        "--n-action-steps",
        type=int,
        help="actions played per decision (as --policy.n_action_steps; default: the checkpoint's)",
    )
    p.add_argument(
        "--torso-offset",
        type=float,
        default=0.0,
        help="rad added to the expert's torso yaw commands from step 8 on (its first turn is done by "
        "then): does the policy take over from a heading a little off the expert's",
    )
    p.add_argument(
        "--span",
        choices=("decoded", "true"),
        default="decoded",
        help="a think-first think=decision policy: true replaces the decoded span's decision (and layout) "
        "with the scene's at every decision",
    )
    p.add_argument(
        "--span-from",
        type=Path,
        metavar="READER",
        help="another think-first think=decision checkpoint fed the same observations: at every decision "
        "the policy acts on the decision READER decoded (its own subtask kept). Reads like READER, "
        "acts like CHECKPOINT: what a policy with one's reading and the other's hand would score",
    )
    p.add_argument(
        "--replan",
        action="store_true",
        help="the policy decides a new chunk at the handover (default: a handover between its decisions first "
        "plays the rest of the chunk it decided before, from the expert's earlier state)",
    )
    p.add_argument("--video", type=Path, help="write each episode's head camera to DIR/EPISODE_POINT.mp4")
    p.add_argument("--out", type=Path, help="also write the per-episode records as JSON lines")
    args = p.parse_args()

    from lerobot.scripts import lerobot_eval
    from tqdm import tqdm, trange

    from lerobot_activearena.envs.manifests import manifest_seed
    from lerobot_activearena.episodes.rollout import run_expert_episode
    from lerobot_activearena.eval.memory_frames import policy_in_env

    lerobot_eval.trange = lambda *a, **k: trange(*a, **{**k, "disable": True})
    adjust = torso_offset(args.torso_offset) if args.torso_offset else None
    points = args.handover.split(",")
    episodes = int_ranges(args.scene_seeds or args.episode_indices)
    as_given = args.scene_seeds is not None
    validation = args.split == "id" and min(episodes) >= 50  # manifest ID 0-49: the protocol's
    scenes = (
        "training scene seeds"
        if as_given
        else ("validation manifest ID" if validation else f"manifest {args.split}")
    )
    if args.span_from and args.span != "decoded":
        p.error("--span-from forces the reader's decoded decision; leave --span at decoded")
    rows = []
    with contextlib.ExitStack() as stack:
        policy, processors, vec, env_cfg, logs = stack.enter_context(
            policy_in_env(
                args.checkpoint, args.task, args.split, expert_channel=True, use_manifest=not as_given
            )
        )
        if args.memory_ablation != "none":
            if not policy.config.history:
                p.error(f"--memory-ablation {args.memory_ablation}: {args.checkpoint} has no memory")
            policy.config.memory_ablation = args.memory_ablation
        if args.n_action_steps is not None:
            if not 1 <= args.n_action_steps <= policy.config.chunk_size:
                p.error(
                    f"--n-action-steps must be in 1..{policy.config.chunk_size}, got {args.n_action_steps}"
                )
            policy.config.n_action_steps = args.n_action_steps
        env = vec.envs[0].unwrapped
        places = isinstance(env.spec_task, InspectAndPlaceTask)
        spans = own = None
        acts_on_span = places and decodes_decision_first(policy)
        if acts_on_span and args.span_from:
            reader, reader_processors, *_ = stack.enter_context(
                policy_in_env(args.span_from, args.task, args.split, use_manifest=not as_given)
            )
            if not decodes_decision_first(reader):
                p.error(f"--span-from {args.span_from}: it does not decode a think=decision span first")
            if args.n_action_steps is not None:
                reader.config.n_action_steps = args.n_action_steps
            # spans: what the policy acts on (the reader's); own: what the policy itself decoded
            spans = SpanWatch(reader, env, force=False)
            own = SpanWatch(policy, env, force=True, source=spans)
            pre = SpanReader(policy, processors[2], reader, reader_processors[2])
            processors = (processors[0], processors[1], pre, processors[3])
        elif acts_on_span:
            spans = SpanWatch(policy, env, force=args.span == "true")
        elif args.span != "decoded" or args.span_from:
            which = f"--span {args.span}" if args.span != "decoded" else "--span-from"
            p.error(f"{which}: {args.checkpoint} does not act on a think=decision span it decodes first")
        for ep in tqdm(episodes, desc="episodes"):
            seed = ep if as_given else env_cfg.seed_base + ep
            scene = ep if as_given else manifest_seed(args.task, args.split, ep)
            expert = run_expert_episode(args.task, scene, args.split)
            subtasks = [int(f["subtask"]) for f in expert.frames]
            for point in points:
                step = handover_step(point, subtasks)
                watch = ReleaseWatch(env) if places else None
                chunk = policy.config.n_action_steps
                reach = ReachWatch(env, step, expert.states, chunk) if places else None
                callbacks = [c for c in (watch, reach) if c is not None]
                if args.video:
                    name = f"{ep}_{point.replace(':', '').replace('+', '_')}.mp4"
                    callbacks.append(VideoWatch(env, args.video / name, step, spans))
                play_with_handover(
                    policy,
                    processors,
                    vec,
                    seed,
                    step,
                    render_callback=lambda v, cs=callbacks: [c(v) for c in cs],
                    adjust_expert=adjust,
                    replan=args.replan,
                )
                for c in callbacks:
                    if isinstance(c, VideoWatch):
                        c.writer.close()
                log = sorted(logs.rglob("*.jsonl"))[0]
                rec = json.loads(log.read_text().splitlines()[-1])
                right = spans.right_after(step) if spans else (0, 0)
                wheres = spans.where_after(step) if spans else []
                if own is not None:
                    own_right, unmatched = own.right_after(step), own.unmatched
                    own.where_after(step)
                    own.unmatched = 0
                rows.append(
                    {
                        "checkpoint": checkpoint_label(args.checkpoint),
                        "span": args.span,
                        "n_action_steps": policy.config.n_action_steps,
                        "scenes": scenes,
                    }
                    | ({"memory_ablation": args.memory_ablation} if args.memory_ablation != "none" else {})
                    | {"episode": ep, "handover": point, "step": step, "expert_steps": expert.length}
                    | ({"replan": True} if args.replan else {})
                    | (
                        {
                            "span_from": checkpoint_label(args.span_from),
                            "own_span_right": own_right[0],
                            "decisions_without_reader_span": unmatched,
                        }
                        if own is not None
                        else {}
                    )
                    | {"span_right": right[0], "span_decisions": right[1]}
                    | ({"span_where_errors": wheres} if wheres else {})
                    | {k: rec[k] for k in ("success", "failure_state", "failure_reason", "steps")}
                    | (where_it_rests(env) | watch.row() | reach.row() if places else {})
                )
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text("".join(json.dumps(r) + "\n" for r in rows))
    memory = "" if args.memory_ablation == "none" else f", memory {args.memory_ablation}"
    if args.n_action_steps is not None:
        memory += f", {args.n_action_steps} actions a decision"
    if args.span != "decoded":
        memory += f", span {args.span}"
    if args.span_from:
        memory += f", acting on the span {args.span_from} decodes"
    if args.replan:
        memory += ", a new decision at the handover"
    if args.torso_offset:
        memory += f", the expert's torso {args.torso_offset:+.3f} rad off from step 8"
    which = f"scene seeds {args.scene_seeds}" if as_given else f"episodes {args.episode_indices}"
    print(f"{args.checkpoint} on {args.task} {args.split}, {which}{memory}:")
    for point in points:
        mine = [r for r in rows if r["handover"] == point]
        states = Counter(r["failure_state"] for r in mine if not r["success"])
        steps = np.mean([r["step"] for r in mine])
        print(
            f"  handover {point:>14} (mean step {steps:5.1f}): {sum(r['success'] for r in mine)} of "
            f"{len(mine)} solved; failures {dict(states)}"
            + (
                f"; the object rests on {dict(Counter(end_place(r) for r in mine))}{missed_places(mine)}{release_angles(mine)}"
                if places
                else ""
            )
        )
        for line in (reach_line(mine), retry_line(mine), lifted_choices(mine)) if places else ():
            if line:
                print(line)
        decisions = sum(r["span_decisions"] for r in mine)
        if decisions:
            print(
                f"    the decoded span named the true decision at {sum(r['span_right'] for r in mine)} of "
                f"{decisions} decisions after the handover"
            )
        wheres = [off for r in mine for off in r.get("span_where_errors", [])]
        for name in sorted({w[1] for w in wheres}):
            off = np.array([w[2:] for w in wheres if w[1] == name])
            print(
                f"    the place the span gives {name} is off by a median {np.median(off[:, 0]):.1f} cm and "
                f"{np.median(off[:, 1]):.1f} deg ({len(off)} decisions)"
            )


if __name__ == "__main__":
    main()
