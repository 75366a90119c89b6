"""How far a policy's pick misses against how far off its torso's heading was, from the records
``handover_eval.py --out`` writes on an inspect-and-place task: one point per episode, the heading's
error after the policy's first chunk (against the expert's own episode) and the hand's nearest
approach to the object, coloured by how far the pick got.

    python analysis/policies/heading_vs_miss.py docs/results/findings/block_cf600_handover.jsonl \\
        --checkpoint block_cf600_layout_action_12_where/002000 --handover start --out docs/img/block_first_turn.png
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

STAGE_COLOURS = {"reach": "tab:red", "grasp": "tab:orange", "lift": "tab:green"}


def points(rows: list[dict]) -> list[tuple[float, float, str]]:
    """(heading error deg, nearest cm, stage) of the rows that carry both."""
    return [
        (r["heading_off_after_first_chunk_deg"], r["reach_nearest_cm"], r["reach_stage"])
        for r in rows
        if r.get("heading_off_after_first_chunk_deg") is not None and "reach_nearest_cm" in r
    ]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("records", type=Path)
    p.add_argument("--checkpoint", help="keep the rows whose checkpoint field is this")
    p.add_argument("--handover", default="start")
    p.add_argument("--tolerance", type=float, default=float(np.degrees(0.12)), help="deg, drawn as a band")
    p.add_argument("--out", type=Path, required=True)
    args = p.parse_args()
    rows = [json.loads(line) for line in args.records.read_text().splitlines() if line.strip()]
    rows = [
        r
        for r in rows
        if r["handover"] == args.handover
        and not r.get("replan")
        and (args.checkpoint is None or r.get("checkpoint") == args.checkpoint)
    ]
    pts = points(rows)
    if not pts:
        p.error(f"no rows of handover {args.handover!r} with a heading error in {args.records}")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 3.6), dpi=120)
    ax.axvspan(-args.tolerance, args.tolerance, color="0.9", label="the demonstrations' off-centre turns")
    for stage, colour in STAGE_COLOURS.items():
        mine = [(h, d) for h, d, s in pts if s == stage]
        if mine:
            ax.scatter(*zip(*mine, strict=True), color=colour, label=f"furthest: {stage} ({len(mine)})")
    ax.set_xlabel("torso heading after the policy's first chunk, minus the expert's (deg)")
    ax.set_ylabel("hand's nearest approach to the block (cm)")
    ax.set_title(f"{args.checkpoint or args.records.stem}, handover {args.handover}", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out)
    print(f"{len(pts)} episodes -> {args.out}")


if __name__ == "__main__":
    main()
