"""Where a rotate-view policy's episodes go wrong: in the search or after it. Splits episodes by
where the expert found the object (on the side it sweeps first, or on the other side after turning
back) and counts, per policy, where the policy's view ended and how the episode ended:

    activearena-eval --policy.type=activearena_expert --env.render_pixels=false --policy.device=cpu \\
        --tasks click_bell_rotate_view --episode-indices 50-79 --videos 0 --out outputs/probe/expert
    python analysis/policies/search_side_outcomes.py outputs/probe/expert outputs/probe/POLICY_A outputs/probe/POLICY_B

Each folder is an ``activearena-eval --out`` of the same episodes (ID split). The view's side is the
sign of the recorded view target's horizontal component (``view_targets``): left, right or centre.
"""

from __future__ import annotations

import argparse
import json
from collections import Counter
from pathlib import Path

SIDE = 0.2  # |horizontal view component| beyond which the view is on a side
TURN = 0.3  # the first step beyond this is the first turn


def side(x: float) -> str:
    return "left" if x < -SIDE else "right" if x > SIDE else "centre"


def first_turn(xs: list[float]) -> str:
    return next((side(x) for x in xs if abs(x) > TURN), "centre")


def records(run: Path, split: str) -> dict[int, dict]:
    path = run / split / "episodes" / "records.jsonl"
    if not path.is_file():
        raise SystemExit(f"{path} not found: pass folders activearena-eval --out wrote")
    return {r["episode"]: r for r in map(json.loads, path.open())}


def outcomes(expert: dict[int, dict], policy: dict[int, dict]) -> dict[str, Counter]:
    """Per expert case ('first side' / 'second side'): counts of the policy's end side and outcome."""
    missing = sorted(set(expert) - set(policy))
    if missing:
        raise SystemExit(f"the policy's run lacks episodes {missing[:5]}...: evaluate the same episodes")
    cases: dict[str, Counter] = {"first side": Counter(), "second side": Counter()}
    for ep, e in expert.items():
        ex = [v[0] for v in e["view_targets"]]
        case = "first side" if side(ex[-1]) == first_turn(ex) else "second side"
        p = policy[ep]
        px = [v[0] for v in p["view_targets"]]
        ended = "expert's side" if side(px[-1]) == side(ex[-1]) else "other side"
        cases[case]["episodes"] += 1
        cases[case][f"view ended on the {ended}"] += 1
        cases[case]["success" if p["success"] else p["failure_state"]] += 1
    return cases


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("expert", type=Path, help="activearena-eval --out of the expert")
    p.add_argument("policies", type=Path, nargs="+", help="activearena-eval --out of policies, same episodes")
    p.add_argument("--split", default="id")
    args = p.parse_args()
    expert = records(args.expert, args.split)
    keys = ["episodes", "view ended on the expert's side", "success", "DM", "CO", "CR"]
    print("| policy | where the expert found it | " + " | ".join(keys) + " |")
    print("|---|---|" + "---|" * len(keys))
    for run in args.policies:
        for case, counts in outcomes(expert, records(run, args.split)).items():
            print(f"| {run.name} | {case} | " + " | ".join(str(counts[k]) for k in keys) + " |")


if __name__ == "__main__":
    main()
