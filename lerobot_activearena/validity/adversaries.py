"""The validity suite's adversaries: policies that must not score, each acting through the public
gym env on scene seeds outside the evaluation manifests: random actions, random targets held for a
chunk, the home pose held, a blind open-loop replay of the expert's actions from another scene, and
the privileged expert with the view fixed at home (the paper's ActiveArena-Fixed row); the
unrestricted expert is the reference that must succeed. ``run_episode`` plays one episode.
"""

from __future__ import annotations

import time
import zlib
from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numpy as np

VALIDITY_SEED_BASE = 900_000  # far above the manifests' EVAL_SEED_START and the datasets' seeds
HOLD_STEPS = 16  # held_random: one target per action chunk
REPLAY_SEED_OFFSET = 1_000_003  # blind_replay: the expert episode comes from seed + k * offset
REPLAY_TRIES = 5  # offsets k = 1..REPLAY_TRIES until the expert succeeds there

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
    from ..episodes.rollout import run_expert_episode

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


def _replay(env, other: int, actions: np.ndarray) -> Act:
    env.replay_seed = other  # reported in the episode record
    return lambda obs, t: actions[min(t, len(actions) - 1)]


def _blind_replay(env, obs, task, split, seed) -> Act:
    return _replay(env, *replay_actions(task, split, seed))


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


def run_episode(
    task: str, split: str, adversary: str, seed: int, replay: tuple[int, np.ndarray] | None = None
) -> dict:
    """One episode of ``adversary`` on scene seed ``seed`` (played directly, no manifest).
    ``replay``: blind_replay's (seed, actions) of an expert episode to replay, e.g. a training
    demonstration (default: ``replay_actions``)."""
    from ..envs.gym_env import ActiveArenaEnv

    adv = get_adversary(adversary)
    if replay is not None and adversary != "blind_replay":
        raise ValueError(f"replay= is blind_replay's episode to replay; {adversary!r} replays nothing")
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
        act = _replay(env, *replay) if replay is not None else adv.make(env, obs, task, split, int(seed))
        t, info = 0, {}
        while t < env._max_episode_steps:  # the env truncates at its step limit; this is a guard
            obs, _, terminated, truncated, info = env.step(act(obs, t))
            t += 1
            if terminated or truncated:
                break
            if adv.expert_channel and env.expert_gave_up:  # it would hold still until the step limit
                info = {
                    "is_success": False,
                    "failure_state": env.episode.failure_state(),
                    "failure_reason": env.expert_gave_up,
                }
                break
    finally:
        env.close()
    rec = {
        "task": task,
        "split": split,
        "adversary": adversary,
        "seed": int(seed),
        "success": bool(info.get("is_success")),
        "steps": t,
        "failure_state": info.get("failure_state", ""),
        "failure_reason": info.get("failure_reason", ""),
        "seconds": round(time.perf_counter() - t0, 3),
    }
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
