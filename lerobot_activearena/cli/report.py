"""`activearena-report`: leaderboard, failure-state decomposition, per-task tables, chunk-boundary
metric (a self-contained report.html, Markdown, CSV, PNG) from one or more lerobot-eval output folders.

    activearena-report outputs/protocol/expert outputs/protocol/oft --out outputs/report   # activearena-eval runs
    activearena-report expert:id=outputs/eval/expert_id expert:ood=outputs/eval/expert_ood --out outputs/report

With ``--comparison docs/results/leaderboard.json`` the report opens with the memory comparison of that
manifest (its table, the picture of a memory bank it names, and each row's hardware and commands) and
adds the compared rows' committed records to its runs; ``--rows NAME ...`` picks rows, e.g. one pair:

    activearena-report --comparison docs/results/leaderboard.json \\
        --rows small_oft_action_12_grounded small_oft_no_0_grounded --out outputs/report/memory_bell
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ..eval.report import build_report, export_records


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument(
        "runs",
        nargs="*",
        help="an activearena-eval run folder, or [label[:split]=]path of a lerobot-eval output folder",
    )
    p.add_argument(
        "--comparison",
        type=Path,
        metavar="MANIFEST",
        help="open with the memory comparison of a results manifest (docs/results/leaderboard.json) "
        "and add its rows' records",
    )
    p.add_argument("--rows", nargs="+", metavar="NAME", help="with --comparison: these rows only")
    p.add_argument("--out", type=Path, default=Path("outputs/report"))
    p.add_argument(
        "--inline-video-mb",
        type=float,
        default=64.0,
        help="embed rollout videos in report.html up to this many MB in total, link the rest (default 64)",
    )
    p.add_argument(
        "--export-records",
        type=Path,
        metavar="DIR",
        help="also copy each activearena-eval run's small records (run.json, policy config, eval_info.json "
        "without video paths, gzipped episode logs; no checkpoints or videos) to DIR/<run folder>, to commit",
    )
    args = p.parse_args(argv)
    if args.inline_video_mb < 0:
        p.error(f"--inline-video-mb must be >= 0, got {args.inline_video_mb}")
    if args.rows and not args.comparison:
        p.error("--rows picks rows of a --comparison manifest: give --comparison too")
    if not args.runs and not args.comparison:
        p.error("give run folders to report on, or --comparison MANIFEST")
    comparison = None
    if args.comparison:
        from ..eval.results_page import comparison_report

        try:
            specs, comparison = comparison_report(args.comparison, args.rows)
        except (FileNotFoundError, ValueError) as exc:
            p.error(str(exc))
        args.runs = [*args.runs, *specs]
    info = build_report(args.runs, args.out, args.inline_video_mb, comparison)["html"]
    if args.export_records:
        folders = [Path(s.rpartition("=")[2]) for s in args.runs]
        for target in export_records(list(dict.fromkeys(folders)), args.export_records):
            print(f"records: {target}")
    print(
        f"wrote {args.out}/report.html ({info['embedded']} videos embedded, {info['linked']} linked), "
        "report.md, leaderboard.csv, failures.csv, per_task.csv, leaderboard.png, per_task.png"
    )


if __name__ == "__main__":
    main()
