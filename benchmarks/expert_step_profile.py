"""Where an oracle episode's time goes: the expert played through the gym env as activearena-eval
plays it (privileged channel, head image not rendered), profiled with cProfile, one process.

    python benchmarks/expert_step_profile.py --tasks click_bell_rotate_view,place_shoe_rotate_view --episodes 3

Prints steps per second and the share of wall time in physics (mj_step), visibility (the per-step
observation of every registered object), the expert's IK (mink), success / failure checks, and the
rest. Run it with the machine otherwise idle; the shares matter more than the absolute figures.
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import time

from lerobot_activearena.envs.gym_env import ActiveArenaEnv

# (label, profiler key: (file suffix, function name)); cumulative times, so parts may nest
PARTS = [
    ("physics (mj_step)", ("~", "<built-in method mujoco._functions.mj_step>")),
    ("visibility (per-step observation)", ("episodes/episode.py", "_observe")),
    ("expert IK (mink solve)", ("expert/ik.py", "solve")),
]


def play(task: str, episodes: int) -> tuple[int, float]:
    """Steps played and seconds spent in reset (scene sampling, compiling, the expert's plan)."""
    env = ActiveArenaEnv(task=task, expert_channel=True, render_pixels=False)
    steps, reset_s = 0, 0.0
    for k in range(episodes):
        t0 = time.perf_counter()
        obs, _ = env.reset(seed=1000 + k)
        reset_s += time.perf_counter() - t0
        done = False
        while not done:
            obs, _, terminated, truncated, _ = env.step(obs["environment_state"])
            steps += 1
            done = terminated or truncated
    env.close()
    return steps, reset_s


def _cumulative(stats: pstats.Stats, suffix: str, name: str) -> float:
    total = 0.0
    for (file, _line, func), (_cc, _nc, _tt, ct, _callers) in stats.stats.items():
        if func == name and (suffix == "~" and file == "~" or file.endswith(suffix)):
            total += ct
    return total


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument(
        "--tasks", default="click_bell_rotate_view,place_shoe_rotate_view,count_target_press_button"
    )
    p.add_argument("--episodes", type=int, default=3)
    args = p.parse_args()
    for task in args.tasks.split(","):
        play(task, 1)  # warm-up: imports, first compile
        prof = cProfile.Profile()
        t0 = time.perf_counter()
        prof.enable()
        steps, reset_s = play(task, args.episodes)
        prof.disable()
        wall = time.perf_counter() - t0
        stats = pstats.Stats(prof)
        profiled = sum(v[2] for v in stats.stats.values())  # all time seen by the profiler
        print(f"\n{task}: {steps} steps in {wall:.1f} s under the profiler ({steps / wall:.0f} steps/s)")
        shares = [(label, _cumulative(stats, suffix, name) / profiled) for label, (suffix, name) in PARTS]
        shares.append(("episode resets (sampling, compile, plan)", reset_s / wall))
        shares.append(("the rest (controller, checks, expert logic)", 1.0 - sum(s for _, s in shares)))
        for label, share in shares:
            print(f"  {label:44s} {100 * share:5.1f} %")


if __name__ == "__main__":
    main()
