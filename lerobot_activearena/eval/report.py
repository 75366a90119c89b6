"""Build the ActiveArena leaderboard from lerobot-eval runs.

A run is a lerobot-eval output folder (``eval_info.json``, ``videos/``) whose env wrote episode logs
with ``--env.episode_log_dir=<run>/episodes`` (split, failure state, view targets per episode).
Success per task comes from ``eval_info.json``; failure states and the chunk-boundary metric from
the episode logs.
"""

from __future__ import annotations

import csv
import gzip
import json
import math
import os
import shutil
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..annotations.keyframes import CHUNK
from ..tasks.base import CATEGORIES
from .report_html import write_html


@dataclass
class Run:
    label: str
    split: str
    path: Path
    task_success: dict[str, list[bool]] = field(default_factory=dict)  # task -> per-episode success
    task_category: dict[str, str] = field(default_factory=dict)
    videos: dict[str, list[str]] = field(default_factory=dict)
    episodes: list[dict] = field(default_factory=list)


def chunk_jump_deg(view_targets, chunk: int = CHUNK) -> tuple[float, float]:
    """The paper's chunk-boundary discontinuity of one episode: the median over boundaries
    t = chunk, 2*chunk, ... of |target[t] - target[t-1]| in degrees, for the torso yaw and the head
    pitch targets separately. NaN for an episode shorter than one chunk."""
    v = np.asarray(view_targets, float).reshape(-1, 2)
    ts = np.arange(chunk, len(v), chunk)
    if len(ts) == 0:
        return float("nan"), float("nan")
    jumps = np.degrees(np.abs(v[ts] - v[ts - 1]))
    return float(np.median(jumps[:, 0])), float(np.median(jumps[:, 1]))


def mean_chunk_jump(episodes: list[dict]) -> tuple[float, float]:
    """Mean over episodes of the episode-level median jumps (torso, head), in degrees."""
    per = np.array([chunk_jump_deg(e["view_targets"]) for e in episodes] or [[np.nan, np.nan]])
    ok = ~np.isnan(per[:, 0])
    return (float(per[ok, 0].mean()), float(per[ok, 1].mean())) if ok.any() else (float("nan"), float("nan"))


def expand_specs(specs: list[str]) -> list[str]:
    """An activearena-eval run folder (with run.json) stands for its merged splits, under its label."""
    out = []
    for spec in specs:
        label, _, path = spec.rpartition("=")
        run_file = Path(path) / "run.json"
        if run_file.is_file():
            plan = json.loads(run_file.read_text())
            name = label.split(":")[0] if label else plan["label"]
            out += [f"{name}:{s}={Path(path) / s}" for s in plan["splits"]]
        else:
            out.append(spec)
    return out


def _locate(video: str, run_dir: Path) -> str:
    """A video path as lerobot-eval recorded it (absolute, relative to where it ran, or to the run
    folder), made absolute where the file is found."""
    for candidate in (Path(video), run_dir / video, run_dir / "videos" / Path(video).name):
        if candidate.is_file():
            return str(candidate.resolve())
    return video


def load_run(spec: str) -> Run:
    """``spec``: ``[label[:split]=]path``; the split defaults to the one in the episode logs."""
    label, split, path = None, None, spec
    if "=" in spec:
        head, path = spec.split("=", 1)
        label, _, split = head.partition(":")
        split = split or None
    path = Path(path)
    info_path = path / "eval_info.json" if path.is_dir() else path
    run_dir = info_path.parent
    if not info_path.exists():
        raise FileNotFoundError(
            f"{info_path} not found: pass lerobot-eval output folders (with eval_info.json)"
        )
    info = json.loads(info_path.read_text())
    episodes = [json.loads(line) for line in episode_log_lines(run_dir / "episodes") if line.strip()]
    splits = {e["split"] for e in episodes}
    if split is None:
        if len(splits) != 1:
            raise ValueError(
                f"{run_dir}: cannot tell the split ({sorted(splits) or 'no episode logs'}); "
                f"pass it as label:split={run_dir} or run lerobot-eval with "
                f"--env.episode_log_dir={run_dir}/episodes"
            )
        split = splits.pop()
    run = Run(label or run_dir.name, split, run_dir, episodes=episodes)
    for entry in info.get("per_task", []):
        task = entry["task_id"]
        run.task_success[task] = [bool(s) for s in entry["metrics"]["successes"]]
        run.task_category[task] = entry["task_group"]
        run.videos[task] = [_locate(v, run_dir) for v in entry["metrics"].get("video_paths", [])]
    if not run.task_success:
        raise ValueError(f"{info_path} has no per_task results (is it an activearena lerobot-eval run?)")
    return run


def _rate(xs) -> float:
    return 100.0 * float(np.mean(xs)) if len(xs) else float("nan")


def leaderboard(runs: list[Run]) -> tuple[list[str], list[list]]:
    cats = list(CATEGORIES)
    header = ["policy"] + [f"{c} {s}" for c in cats for s in ("ID", "OOD")] + ["Avg ID", "Avg OOD"]
    by_label: dict[str, dict[str, Run]] = defaultdict(dict)
    for r in runs:
        by_label[r.label][r.split] = r
    rows = []
    for label, splits in by_label.items():
        row = [label]
        cells = {}
        for c in cats:
            for s in ("id", "ood"):
                r = splits.get(s)
                rates = [
                    _rate(v) for t, v in (r.task_success.items() if r else []) if r.task_category[t] == c
                ]
                cells[(c, s)] = float(np.mean(rates)) if rates else float("nan")
        for c in cats:
            row += [cells[(c, "id")], cells[(c, "ood")]]
        for s in ("id", "ood"):
            r = splits.get(s)
            rates = [_rate(v) for v in r.task_success.values()] if r else []
            row.append(float(np.mean(rates)) if rates else float("nan"))  # task-macro mean
        rows.append(row)
    return header, rows


def failure_table(runs: list[Run]) -> tuple[list[str], list[list]]:
    header = [
        "policy",
        "split",
        "failures",
        "DM %",
        "CO %",
        "CR %",
        "torso chunk jump (deg)",
        "head chunk jump (deg)",
    ]
    rows = []
    for r in runs:
        fails = [e["failure_state"] for e in r.episodes if not e["success"]]
        n = len(fails)
        pct = [100.0 * fails.count(k) / n if n else float("nan") for k in ("DM", "CO", "CR")]
        rows.append([r.label, r.split.upper(), n, *pct, *mean_chunk_jump(r.episodes)])
    return header, rows


def per_task_table(runs: list[Run]) -> tuple[list[str], list[list]]:
    """One row per task, one column per policy and split: policies side by side."""
    cols = [(r.label, r.split) for r in runs]
    header = ["category", "task"] + [f"{label} {split.upper()}" for label, split in cols]
    cats = {t: c for r in runs for t, c in r.task_category.items()}
    rows = []
    for t in sorted(
        cats, key=lambda t: (list(CATEGORIES).index(cats[t]) if cats[t] in CATEGORIES else 99, t)
    ):
        rows.append(
            [cats[t], t] + [_rate(r.task_success[t]) if t in r.task_success else float("nan") for r in runs]
        )
    return header, rows


def _fmt(x, digits: int = 1) -> str:
    if isinstance(x, float):
        return "-" if math.isnan(x) else f"{x:.{digits}f}"
    return str(x)


def markdown(header, rows) -> str:
    digits = [2 if "(deg)" in h else 1 for h in header]  # chunk jumps: the paper reports hundredths
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_fmt(x, d) for x, d in zip(row, digits, strict=True)) + " |" for row in rows]
    return "\n".join(lines)


def write_csv(path: Path, header, rows) -> None:
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows([[("" if isinstance(x, float) and math.isnan(x) else x) for x in row] for row in rows])


def bar_chart(path: Path, header, rows, title: str = "ActiveArena success by category (task-macro)") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cols = header[1:]
    x = np.arange(len(cols))
    width = 0.8 / max(1, len(rows))
    fig, ax = plt.subplots(figsize=(max(8, len(cols) * 0.8), 4))
    for k, row in enumerate(rows):
        vals = [0.0 if (isinstance(v, float) and math.isnan(v)) else v for v in row[1:]]
        ax.bar(x + k * width - 0.4 + width / 2, vals, width, label=row[0])
    ax.set_xticks(x, cols, rotation=45, ha="right")
    ax.set_ylabel("success %")
    ax.set_ylim(0, 100)
    ax.set_title(title)
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _relative(path: str, out: Path) -> str:
    """A link from the report folder: relative, so the folder (with the runs beside it) can move."""
    p = Path(path)
    return os.path.relpath(p, out.resolve()) if p.is_absolute() else path


def merge_runs(runs: list[Run]) -> list[Run]:
    """Runs with the same label and split become one (e.g. a policy trained and evaluated per task,
    one run folder per task); a task evaluated twice under one label and split is refused."""
    merged: dict[tuple[str, str], Run] = {}
    for r in runs:
        key = (r.label, r.split)
        if key not in merged:
            merged[key] = r
            continue
        m = merged[key]
        if twice := sorted(set(m.task_success) & set(r.task_success)):
            raise ValueError(
                f"{r.label} {r.split}: {', '.join(twice)} in both {m.path} and {r.path}; "
                "give the runs different labels (label=path)"
            )
        merged[key] = Run(
            r.label,
            r.split,
            m.path,
            {**m.task_success, **r.task_success},
            {**m.task_category, **r.task_category},
            {**m.videos, **r.videos},
            m.episodes + r.episodes,
        )
    return list(merged.values())


COMPARISON_NOTE = (
    "The memory comparison: the same policy with and without memory, and with its memory images blanked, "
    "success % (ID / OOD) per task, ID failures by state, and how each row was trained."
)


def build_report(
    run_specs: list[str], out: Path, inline_video_mb: float = 64.0, comparison: dict | None = None
) -> dict:
    """The report of ``run_specs``; ``comparison`` (``results_page.comparison_report``'s second
    value) opens it with the memory comparison's table, picture and commands."""
    runs = merge_runs([load_run(s) for s in expand_specs(run_specs)])
    out.mkdir(parents=True, exist_ok=True)
    lb, fl, pt = leaderboard(runs), failure_table(runs), per_task_table(runs)
    write_csv(out / "leaderboard.csv", *lb)
    write_csv(out / "failures.csv", *fl)
    write_csv(out / "per_task.csv", *pt)
    bar_chart(out / "leaderboard.png", *lb)
    tasks = [row[1] for row in pt[1]]  # the chart's groups are tasks, its bars the policy / split columns
    bars = [[col] + [row[2 + k] for row in pt[1]] for k, col in enumerate(pt[0][2:])]
    bar_chart(out / "per_task.png", ["", *tasks], bars, title="ActiveArena success by task")
    sections = [
        (
            "Success by category",
            "Success rate (%) per category, ID and OOD; Avg = task-macro mean over tasks.",
            lb,
            "leaderboard.png",
        ),
        (
            "Failure states among failed episodes",
            "DM: a task-relevant object was never observed; CO: all observed, the final view misses some; "
            "CR: the final view covers all, the task still failed. Chunk jump (the paper's action-continuity "
            f"metric): per episode the median jump of the commanded target at the {CHUNK}-step chunk "
            "boundaries, then the mean over episodes; torso yaw and head pitch separately.",
            fl,
            None,
        ),
        ("Per task (success %)", "One column per policy and split.", pt, "per_task.png"),
    ]
    commands = []
    if comparison:
        picture, caption = comparison["picture"] or (None, "")
        if picture:
            shutil.copyfile(picture, out / "memory_bank.png")
        text = COMPARISON_NOTE + (f" Picture: {caption}" if caption else "")
        sections.insert(
            0, ("Memory comparison", text, comparison["table"], "memory_bank.png" if picture else None)
        )
        commands = comparison["commands"]
    videos = [  # (task, caption, file, link relative to the report)
        (t, f"{r.label} {r.split.upper()}", Path(p), _relative(p, out))
        for r in runs
        for t, paths in sorted(r.videos.items())
        for p in paths
    ]
    md = ["# ActiveArena leaderboard", ""]
    for k, (title, text, table, png) in enumerate(sections):
        md += ([] if k == 0 and not comparison else [f"## {title}", ""]) + [text, "", markdown(*table), ""]
        md += [f"![{title}]({png})", ""] if png else []
    if commands:
        md += ["## How each compared row was made", ""]
        for policy, hardware, lines in commands:
            md += [f"### {policy}", "", f"Hardware: {hardware}", "", "```bash", *lines, "```", ""]
    md += ["## Rollout videos", ""]
    md += [f"- {cap} `{t}`: [{path.name}]({link})" for t, cap, path, link in videos] or ["(none saved)"]
    md += [
        "",
        "The same report as one self-contained page (tables, charts and videos inline): report.html",
        "",
    ]
    (out / "report.md").write_text("\n".join(md))
    html_info = write_html(
        out, sections, videos, lambda x, h: _fmt(x, 2 if "(deg)" in h else 1), inline_video_mb, commands
    )
    return {"leaderboard": lb, "failures": fl, "per_task": pt, "html": html_info}


def episode_log_lines(folder: Path) -> list[str]:
    """The lines of a folder's episode logs, ``*.jsonl`` and gzipped ``*.jsonl.gz`` (exported records)."""
    lines = []
    for f in sorted(folder.glob("*.jsonl")):
        lines += f.read_text().splitlines()
    for f in sorted(folder.glob("*.jsonl.gz")):
        lines += gzip.decompress(f.read_bytes()).decode().splitlines()
    return lines


def export_records(run_dirs: list[Path], dest: Path) -> list[Path]:
    """The small records behind a table, to commit beside it: per activearena-eval run folder its
    ``run.json``, ``policy/config.json`` and per split ``eval_info.json`` (video paths removed: the
    videos stay behind) and ``episodes/*.jsonl`` gzipped (``.jsonl.gz``, byte-reproducible: no time
    stamp; the per-step targets make a 35-task protocol's logs ~25 MB raw); no checkpoints, no
    videos. Copies go to ``dest/<run folder name>``, which must not exist yet."""
    written = []
    for run_dir in run_dirs:
        run_dir = Path(run_dir)
        if not (run_dir / "run.json").is_file():
            raise ValueError(f"{run_dir}: no run.json; --export-records takes activearena-eval run folders")
        target = dest / run_dir.name
        if target.exists():
            raise FileExistsError(f"{target} exists; remove it to export {run_dir} again")
        plan = json.loads((run_dir / "run.json").read_text())
        target.mkdir(parents=True)
        shutil.copy2(run_dir / "run.json", target / "run.json")
        if (run_dir / "policy" / "config.json").is_file():
            (target / "policy").mkdir()
            shutil.copy2(run_dir / "policy" / "config.json", target / "policy" / "config.json")
        for split in plan["splits"]:
            info = json.loads((run_dir / split / "eval_info.json").read_text())
            for entry in info.get("per_task", []):
                entry["metrics"].pop("video_paths", None)
            info.get("overall", {}).pop("video_paths", None)
            (target / split / "episodes").mkdir(parents=True)
            (target / split / "eval_info.json").write_text(json.dumps(info, indent=2))
            for log in sorted((run_dir / split / "episodes").glob("*.jsonl")):
                packed = gzip.compress(log.read_bytes(), compresslevel=9, mtime=0)
                (target / split / "episodes" / f"{log.name}.gz").write_bytes(packed)
        written.append(target)
    return written
