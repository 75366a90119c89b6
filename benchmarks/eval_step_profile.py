"""Where an `activearena-eval` vector step's time goes: the run's own command, in this process (one
worker), with timers around each part of LeRobot's rollout loop.

    python benchmarks/eval_step_profile.py -- --policy.type=activearena_oft --policy.vlm_path=DIR \
        --policy.device=cuda --tasks=click_bell_rotate_view --episodes 16 --batch-size 16 --async-envs \
        --videos 0 --out /tmp/profile_run --overwrite

``--eager-frames`` processes every env step's frames in the preprocessor (the policy otherwise runs
the image processor only at chunk boundaries and memory writes): the A/B of that deferral.

Everything after ``--`` goes to activearena-eval (``--workers`` is forced to 1, so the shard runs here).
Prints, per part, the seconds over all rollouts, the milliseconds per vector step and the share of
the rollouts' wall time, then env steps/s (vector steps x envs, as LeRobot steps every env until all
are done). On CUDA every timer synchronises, so GPU work is charged to the part that queued it.
"""

from __future__ import annotations

import argparse
import functools
import statistics
import time
from collections import Counter, defaultdict

import torch

SECONDS: dict[str, float] = defaultdict(float)
CALLS: Counter = Counter()
EACH: dict[str, list[float]] = defaultdict(list)
ENVS: list[int] = []


def _sync() -> None:
    if torch.cuda.is_available() and torch.cuda.is_initialized():
        torch.cuda.synchronize()


def timed(name: str, fn):
    if getattr(fn, "_profiled", False):
        return fn

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        _sync()
        t0 = time.perf_counter()
        out = fn(*args, **kwargs)
        _sync()
        SECONDS[name] += time.perf_counter() - t0
        CALLS[name] += 1
        EACH[name].append(time.perf_counter() - t0)
        return out

    wrapper._profiled = True
    return wrapper


PARTS = {
    "env.reset": "env reset (scene build per episode, in the workers)",
    "env.step": "env step: worker processes (physics, IK, render), observations back",
    "env.call": "env.call (task text, each step)",
    "preprocess_observation": "LeRobot's preprocess_observation (numpy -> float tensors)",
    "env_pre": "env preprocessor",
    "pre": "policy preprocessor (image processor, tokenizer, normalise, to device)",
    "select_action": "policy.select_action (with its new chunks)",
    "predict_action_chunk": "  of which new chunks (predict_action_chunk)",
    "ensure_pixels": "  of which env frames through the image processor (ensure_pixels)",
    "post": "policy postprocessor",
    "env_post": "env postprocessor",
    "callback": "per-step policy stats callback",
}


def instrument() -> None:
    from lerobot.scripts import lerobot_eval

    real_rollout = lerobot_eval.rollout
    lerobot_eval.preprocess_observation = timed(
        PARTS["preprocess_observation"], lerobot_eval.preprocess_observation
    )

    def rollout(env, policy, env_pre, env_post, pre, post, **kwargs):
        env.reset = timed(PARTS["env.reset"], env.reset)
        env.step = timed(PARTS["env.step"], env.step)
        env.call = timed(PARTS["env.call"], env.call)
        policy.select_action = timed(PARTS["select_action"], policy.select_action)
        policy.predict_action_chunk = timed(PARTS["predict_action_chunk"], policy.predict_action_chunk)
        if hasattr(policy, "ensure_pixels"):
            policy.ensure_pixels = timed(PARTS["ensure_pixels"], policy.ensure_pixels)
        if kwargs.get("predicted_latents_callback") is not None:
            kwargs["predicted_latents_callback"] = timed(
                PARTS["callback"], kwargs["predicted_latents_callback"]
            )
        ENVS.append(env.num_envs)
        t0 = time.perf_counter()
        out = real_rollout(
            env,
            policy,
            timed(PARTS["env_pre"], env_pre),
            timed(PARTS["env_post"], env_post),
            timed(PARTS["pre"], pre),
            timed(PARTS["post"], post),
            **kwargs,
        )
        SECONDS["rollouts"] += time.perf_counter() - t0
        return out

    lerobot_eval.rollout = rollout


def report(command_s: float) -> None:
    steps = CALLS[PARTS["env.step"]]
    wall = SECONDS["rollouts"]
    if not steps or not wall:
        raise SystemExit("no rollout ran: is every episode of --out already recorded? add --overwrite")
    env_steps = steps * (sum(ENVS) / len(ENVS))
    print(f"\n{len(ENVS)} rollouts, {steps} vector steps of {ENVS[0]} envs, {wall:.1f} s inside rollout()")
    print(f"{'part':<75} {'s':>8} {'ms/step':>8} {'share':>6}")
    accounted = 0.0
    for key, name in PARTS.items():
        if name in SECONDS:
            s = SECONDS[name]
            accounted += 0 if key in ("predict_action_chunk", "ensure_pixels") else s
            print(f"{name:<75} {s:8.2f} {1000 * s / steps:8.1f} {100 * s / wall:5.1f}%")
    rest = wall - accounted
    print(
        f"{'the loop itself (the rest)':<75} {rest:8.2f} {1000 * rest / steps:8.1f} {100 * rest / wall:5.1f}%"
    )
    chunks = EACH[PARTS["predict_action_chunk"]]
    if chunks:
        print(
            f"new chunks: {len(chunks)} ({1000 * sum(chunks) / len(chunks):.0f} ms each; the first "
            f"{1000 * chunks[0]:.0f} ms, the median {1000 * statistics.median(chunks):.0f} ms)"
        )
    resets = EACH[PARTS["env.reset"]]
    print(
        "env resets (the first of a vector env starts its worker processes): "
        + ", ".join(f"{t:.1f}" for t in resets)
        + " s"
    )
    print(f"env steps/s inside the rollouts: {env_steps / wall:.1f} ({env_steps:.0f} env steps)")
    print(f"env steps/s inside the rollouts, resets left out: {env_steps / (wall - sum(resets)):.1f}")
    print(
        f"the whole command: {command_s:.1f} s (policy loads, env start-up, rollouts, merge; not this script's imports) = "
        f"{env_steps / command_s:.1f} env steps/s"
    )


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("eval_args", nargs=argparse.REMAINDER, help="-- then activearena-eval's arguments")
    p.add_argument(
        "--eager-frames",
        action="store_true",
        help="the preprocessor runs the image processor on every env step's frames (no deferral)",
    )
    args = p.parse_args()
    if args.eager_frames:
        from lerobot_activearena.policies.activearena_vla import processor_activearena_vla as proc

        post_init = proc.ActiveArenaVLMInputsStep.__post_init__

        def eager(step):
            post_init(step)
            step.defer_env_frames = False

        proc.ActiveArenaVLMInputsStep.__post_init__ = eager
    eval_args = [a for a in args.eval_args if a != "--"]
    eval_args = [a for a in eval_args if not a.startswith("--workers")] + ["--workers", "1"]
    instrument()
    from lerobot_activearena.cli.eval import main as activearena_eval

    t0 = time.perf_counter()
    activearena_eval(eval_args)
    report(time.perf_counter() - t0)


if __name__ == "__main__":
    main()
