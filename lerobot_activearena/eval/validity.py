"""The benchmark's validity suite: adversarial policies that must not score. Each adversary acts
through the public gym env on scene seeds outside the evaluation manifests: random actions,
random targets held for a chunk, the home pose held, a blind open-loop replay of the expert's
actions from another scene, and the privileged expert with the view fixed at home (the paper's
ActiveArena-Fixed row); the unrestricted expert is the reference row that must succeed. A task
an adversary solves can be gamed without active perception.
"""

from __future__ import annotations

import collections
import csv
import json
import multiprocessing as mp
import re
import time
import zlib
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

VALIDITY_SEED_BASE = 900_000  # far above the manifests' EVAL_SEED_START and the datasets' seeds
HOLD_STEPS = 16  # held_random: one target per action chunk
REPLAY_SEED_OFFSET = 1_000_003  # blind_replay: the expert episode comes from seed + k * offset
REPLAY_TRIES = 5  # offsets k = 1..REPLAY_TRIES until the expert succeeds there
EPISODES_FILE = "episodes.jsonl"
REASON_CHARS = 80

# act(obs, t) -> 18-D action; built once per episode by the adversary from the reset env
Act = Callable[[dict, int], np.ndarray]


@dataclass(frozen=True)
class Adversary:
    name: str
    description: str
    make: Callable[..., Act]  # make(env, obs, task, split, seed) -> act
    fixed_view: bool = False
    expert_channel: bool = False


def _rng(name: str, task: str, split: str, seed: int) -> np.random.Generator:
    """Deterministic per episode (crc32, not hash(): the same in every process)."""
    return np.random.default_rng([int(seed), zlib.crc32(f"{name}/{task}/{split}".encode())])


def _random(env, obs, task, split, seed) -> Act:
    rng, low, high = _rng("random", task, split, seed), env.action_space.low, env.action_space.high
    return lambda obs, t: rng.uniform(low, high)


def _held_random(env, obs, task, split, seed) -> Act:
    rng, low, high = _rng("held_random", task, split, seed), env.action_space.low, env.action_space.high
    target = rng.uniform(low, high)

    def act(obs, t):
        nonlocal target
        if t and t % HOLD_STEPS == 0:
            target = rng.uniform(low, high)
        return target

    return act


def _still(env, obs, task, split, seed) -> Act:
    home = env.sim.home_action().copy()
    return lambda obs, t: home


def replay_actions(task: str, split: str, seed: int) -> tuple[int, np.ndarray]:
    """The (seed, actions) of a successful expert episode of ``task``/``split`` on another seed:
    seed + k * REPLAY_SEED_OFFSET for the first k in 1..REPLAY_TRIES where the expert succeeds."""
    from ..tasks.rollout import run_expert_episode

    tried = []
    for k in range(1, REPLAY_TRIES + 1):
        other = int(seed) + k * REPLAY_SEED_OFFSET
        try:
            r = run_expert_episode(task, other, split)
        except Exception as exc:  # an unsamplable seed: try the next one
            tried.append(f"{other}: {type(exc).__name__}")
            continue
        if r.success and len(r.actions):
            return other, r.actions
        tried.append(f"{other}: {r.failure}")
    raise RuntimeError(f"blind_replay: the expert failed on every replay seed of {task}/{split}: {tried}")


def _blind_replay(env, obs, task, split, seed) -> Act:
    other, actions = replay_actions(task, split, seed)
    env.replay_seed = other  # reported in the episode record
    return lambda obs, t: actions[min(t, len(actions) - 1)]


def _expert(env, obs, task, split, seed) -> Act:
    return lambda obs, t: obs["environment_state"]


ADVERSARIES: dict[str, Adversary] = {
    a.name: a
    for a in (
        Adversary("random", "a uniformly random action every step", _random),
        Adversary("held_random", f"a uniformly random target held for {HOLD_STEPS} steps", _held_random),
        Adversary("still", "the home action held", _still),
        Adversary("blind_replay", "the expert's actions from another seed, open loop", _blind_replay),
        Adversary(
            "fixed_view_expert",
            "the privileged expert with head and torso fixed at home",
            _expert,
            fixed_view=True,
            expert_channel=True,
        ),
        Adversary("expert", "the privileged expert (reference: must succeed)", _expert, expert_channel=True),
    )
}
LOOK_AT_NOTHING = ("random", "held_random", "still", "blind_replay")


def get_adversary(name: str) -> Adversary:
    if name not in ADVERSARIES:
        raise ValueError(f"unknown adversary {name!r}; valid adversaries: {', '.join(ADVERSARIES)}")
    return ADVERSARIES[name]


def run_episode(task: str, split: str, adversary: str, seed: int) -> dict:
    """One episode of ``adversary`` on scene seed ``seed`` (played directly, no manifest)."""
    from ..envs.gym_env import ActiveArenaEnv

    adv = get_adversary(adversary)
    t0 = time.perf_counter()
    env = ActiveArenaEnv(
        task=task,
        split=split,
        use_manifest=False,
        render_pixels=False,
        fixed_view=adv.fixed_view,
        expert_channel=adv.expert_channel,
    )
    env.replay_seed = None
    try:
        obs, _ = env.reset(seed=int(seed))
        act = adv.make(env, obs, task, split, int(seed))
        t, info = 0, {}
        while t < env._max_episode_steps:  # the env truncates at its step limit; this is a guard
            obs, _, terminated, truncated, info = env.step(act(obs, t))
            t += 1
            if terminated or truncated:
                break
    finally:
        env.close()
    rec = dict(
        task=task,
        split=split,
        adversary=adversary,
        seed=int(seed),
        success=bool(info.get("is_success")),
        steps=t,
        failure_state=info.get("failure_state", ""),
        failure_reason=info.get("failure_reason", ""),
        seconds=round(time.perf_counter() - t0, 3),
    )
    if env.replay_seed is not None:
        rec["replay_seed"] = env.replay_seed
    return rec


# ---- seeds ---------------------------------------------------------------------------------------
def validity_seeds(n: int, base: int = VALIDITY_SEED_BASE) -> list[int]:
    return list(range(base, base + n))


def check_outside_manifests(tasks: Iterable[str], seeds: Iterable[int]) -> None:
    """Raise if any seed is an evaluation seed of a task (any split of its manifest)."""
    from ..envs.manifests import load_manifest, manifest_path
    from ..tasks.base import SPLITS

    seeds = set(seeds)
    for task in tasks:
        if not manifest_path(task).exists():  # no manifest yet: nothing to collide with
            continue
        for split in SPLITS:
            try:
                clash = seeds.intersection(load_manifest(task, split))
            except KeyError:
                continue
            if clash:
                raise ValueError(
                    f"validity seeds {sorted(clash)[:5]} are evaluation seeds of {task}/{split}; "
                    f"use seeds outside the manifests (the default base is {VALIDITY_SEED_BASE})"
                )


# ---- suite ---------------------------------------------------------------------------------------
def _key(rec: dict) -> tuple:
    return rec["task"], rec["split"], rec["adversary"], int(rec["seed"])


def _run_job(job: tuple) -> dict:
    """Pool worker: an exception is recorded (``error``), not raised; a resumed run retries it."""
    task, split, adversary, seed = job
    t0 = time.perf_counter()
    try:
        return run_episode(task, split, adversary, seed)
    except Exception as exc:
        return dict(
            task=task,
            split=split,
            adversary=adversary,
            seed=int(seed),
            success=False,
            steps=0,
            failure_state="ERR",
            failure_reason=f"{type(exc).__name__}: {exc}"[:300],
            seconds=round(time.perf_counter() - t0, 3),
            error=True,
        )


def load_records(path: Path) -> dict[tuple, dict]:
    """Finished episodes of ``episodes.jsonl`` by key; a line cut by a kill is dropped (and the
    file rewritten without it, so appends start on a fresh line). Errors are not kept."""
    if not path.exists():
        return {}
    text = path.read_text()
    good, out = [], {}
    for line in text.splitlines():
        try:
            rec = json.loads(line)
            key = _key(rec)
        except (ValueError, KeyError, TypeError):
            continue
        good.append(line)
        if not rec.get("error"):
            out[key] = rec
    if text and (not text.endswith("\n") or len(good) != len(text.splitlines())):
        path.write_text("".join(g + "\n" for g in good))
    return out


def run_suite(
    tasks: Sequence[str],
    adversaries: Sequence[str],
    seeds: int | Iterable[int],
    splits: Sequence[str] = ("id",),
    out_dir: str | Path = "outputs/validity",
    workers: int = 2,
) -> list[dict]:
    """Run every (task, split, adversary, seed) episode not yet in ``out_dir/episodes.jsonl``,
    appending one line per finished episode; return the records of all requested episodes.
    ``seeds``: a count (seeds VALIDITY_SEED_BASE..) or explicit seeds. ``workers <= 1`` runs in
    this process."""
    from tqdm import tqdm

    for a in adversaries:
        get_adversary(a)
    seeds = validity_seeds(seeds) if isinstance(seeds, int) else [int(s) for s in seeds]
    check_outside_manifests(tasks, seeds)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / EPISODES_FILE
    done = load_records(path)
    jobs = [(t, sp, a, s) for t in tasks for sp in splits for a in adversaries for s in seeds]
    todo = [j for j in jobs if j not in done]
    if len(todo) < len(jobs):
        print(f"resuming {path}: {len(jobs) - len(todo)} of {len(jobs)} episodes already recorded")
    with open(path, "a") as f, tqdm(total=len(todo), desc="validity episodes", unit="ep") as bar:

        def record(rec):
            f.write(json.dumps(rec) + "\n")
            f.flush()
            if not rec.get("error"):
                done[_key(rec)] = rec
            bar.update()
            bar.set_postfix_str(f"{rec['task'][:20]}/{rec['adversary']}", refresh=False)

        if workers <= 1 or len(todo) <= 1:
            for job in todo:
                record(_run_job(job))
        else:
            # spawn: fresh interpreters, no forked MuJoCo/EGL state
            with mp.get_context("spawn").Pool(min(workers, len(todo))) as pool:
                for rec in pool.imap_unordered(_run_job, todo, chunksize=1):
                    record(rec)
    errors = [j for j in jobs if j not in done]
    if errors:
        print(f"{len(errors)} episode(s) raised an error (see 'ERR' lines in {path}; a re-run retries them)")
    return [done.get(j) or _error_stub(j) for j in jobs]


def _error_stub(job: tuple) -> dict:
    task, split, adversary, seed = job
    return dict(
        task=task,
        split=split,
        adversary=adversary,
        seed=seed,
        success=False,
        steps=0,
        failure_state="ERR",
        failure_reason="error (see episodes.jsonl)",
        seconds=0.0,
        error=True,
    )


# ---- summary -------------------------------------------------------------------------------------
def _short_reason(reason: str) -> str:
    """Group reasons that differ only in coordinates; cut long ones."""
    r = re.sub(r"\[[^\]]*\]", "[...]", reason or "").strip()
    return r if len(r) <= REASON_CHARS else r[: REASON_CHARS - 3] + "..."


def target_text(adversary: str) -> str:
    if adversary in ("random", "held_random", "still"):
        return "<= 1 in 50 (2%)"
    return {"blind_replay": "<= 10%", "fixed_view_expert": "<= 5%", "expert": ">= 95%"}[adversary]


def targets_met(row: dict) -> bool:
    """The validity targets: look-at-nothing adversaries at most 1 success in up to 50 episodes
    (2 % beyond), blind replay at most 10 %, the fixed-view expert at most 5 %, the expert at
    least 95 %. A row with no finished episode misses its target."""
    n, k, a = row["episodes"], row["successes"], row["adversary"]
    if n == 0:
        return False
    if a in ("random", "held_random", "still"):
        return k <= 1 if n <= 50 else k <= 0.02 * n
    if a == "blind_replay":
        return k <= 0.10 * n
    if a == "fixed_view_expert":
        return k <= 0.05 * n
    if a == "expert":
        return k >= 0.95 * n
    raise ValueError(f"no validity target for adversary {a!r}")


def summarise(records: Iterable[dict]) -> list[dict]:
    """One row per (task, split, adversary), in adversary order within each task and split."""
    groups: dict[tuple, list[dict]] = collections.defaultdict(list)
    for r in records:
        groups[(r["task"], r["split"], r["adversary"])].append(r)
    order = list(ADVERSARIES)
    rows = []
    for (task, split, adv), rs in sorted(
        groups.items(), key=lambda kv: (kv[0][0], kv[0][1], order.index(kv[0][2]))
    ):
        ok = [r for r in rs if not r.get("error")]
        k = sum(bool(r["success"]) for r in ok)
        states = collections.Counter(r["failure_state"] for r in ok if not r["success"])
        reasons = collections.Counter(_short_reason(r["failure_reason"]) for r in ok if not r["success"])
        row = dict(
            task=task,
            split=split,
            adversary=adv,
            episodes=len(ok),
            successes=k,
            success_rate=k / len(ok) if ok else float("nan"),
            errors=len(rs) - len(ok),
            failure_states=dict(sorted(states.items())),
            failure_reasons=reasons.most_common(3),
            seconds_per_episode=sum(r["seconds"] for r in ok) / max(1, len(ok)),
            target=target_text(adv),
        )
        row["met"] = targets_met(row)
        rows.append(row)
    return rows


def markdown_table(rows: list[dict]) -> str:
    lines = [
        "| task | split | adversary | success | failure states | most common failure reasons | s/episode "
        "| target | met |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        states = ", ".join(f"{s} {n}" for s, n in r["failure_states"].items()) + (
            f", ERR {r['errors']}" if r["errors"] else ""
        )
        reasons = "; ".join(f"{n}x {t}" for t, n in r["failure_reasons"]).replace("|", "/")
        lines.append(
            f"| {r['task']} | {r['split']} | {r['adversary']} | {r['successes']}/{r['episodes']} "
            f"({100 * r['success_rate']:.0f}%) | {states} | {reasons} | {r['seconds_per_episode']:.2f} "
            f"| {r['target']} | {'ok' if r['met'] else 'MISSED'} |"
        )
    return "\n".join(lines)


def write_report(rows: list[dict], out_dir: str | Path) -> str:
    """Write ``validity.md`` and ``validity.csv`` under ``out_dir``; return the Markdown table."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    table = markdown_table(rows)
    (out_dir / "validity.md").write_text("# ActiveArena validity suite\n\n" + table + "\n")
    with open(out_dir / "validity.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(
            [
                "task",
                "split",
                "adversary",
                "episodes",
                "successes",
                "success_rate",
                "DM",
                "CO",
                "CR",
                "errors",
                "seconds_per_episode",
                "target",
                "met",
                "failure_reasons",
            ]
        )
        for r in rows:
            fs = r["failure_states"]
            w.writerow(
                [
                    r["task"],
                    r["split"],
                    r["adversary"],
                    r["episodes"],
                    r["successes"],
                    f"{r['success_rate']:.3f}",
                    fs.get("DM", 0),
                    fs.get("CO", 0),
                    fs.get("CR", 0),
                    r["errors"],
                    f"{r['seconds_per_episode']:.3f}",
                    r["target"],
                    "ok" if r["met"] else "MISSED",
                    "; ".join(f"{n}x {t}" for t, n in r["failure_reasons"]),
                ]
            )
    return table


def missed(rows: list[dict]) -> list[str]:
    return [
        f"{r['task']}/{r['split']}/{r['adversary']} ({r['successes']}/{r['episodes']}, target {r['target']})"
        for r in rows
        if not r["met"]
    ]
