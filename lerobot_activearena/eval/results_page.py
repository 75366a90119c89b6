"""The leaderboard of the README and ``docs/results.md``, generated from committed evaluation records.

A manifest (``docs/results/leaderboard.json``) names each row's records (``activearena-eval`` run folders
exported with ``activearena-report --export-records``), what it was trained on, where, and the commands
that reproduce it. Scores are never typed by hand: they are read from the records here and written
between ``<!-- generated:NAME -->`` and ``<!-- /generated:NAME -->`` markers in the pages, so a test
can hold each committed page equal to what this module writes.
"""

from __future__ import annotations

import json
import os
import re
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

from .report import expand_specs, load_run

ROW_FIELDS = ("name", "policy", "records", "data", "training", "hardware", "commands")
FAILURES = ("DM", "CO", "CR")


@dataclass
class Row:
    """One leaderboard row: the manifest's words and the scores read from its records."""

    name: str
    policy: str
    records: list[str]
    data: str
    training: str
    hardware: str
    commands: list[str]
    memory: str = ""
    note: str = ""
    leaderboard: bool = True  # False: an ablation, shown in the comparison and the rows only
    # task -> split -> per-episode success; split -> failure state -> count
    success: dict[str, dict[str, list[bool]]] = field(default_factory=dict)
    failures: dict[str, dict[str, int]] = field(default_factory=dict)
    task_failures: dict[str, dict[str, dict[str, int]]] = field(
        default_factory=dict
    )  # task -> split -> state


def load_rows(manifest: Path) -> tuple[dict, list[Row]]:
    """The manifest and its rows with their scores; record folders are relative to the manifest's
    ``records`` folder."""
    spec = json.loads(manifest.read_text())
    records_dir = manifest.parent / spec.get("records_dir", "records")
    rows = []
    for i, entry in enumerate(spec["rows"]):
        missing = [f for f in ROW_FIELDS if f not in entry]
        if missing:
            raise ValueError(f"{manifest}: row {i} ({entry.get('name', '?')}) lacks {missing}")
        row = Row(**entry)
        success: dict[str, dict[str, list[bool]]] = defaultdict(lambda: defaultdict(list))
        failures: dict[str, dict[str, int]] = defaultdict(lambda: dict.fromkeys(FAILURES, 0))
        per_task: dict = defaultdict(lambda: defaultdict(lambda: dict.fromkeys(FAILURES, 0)))
        for record in row.records:
            folder = records_dir / record
            if not (folder / "run.json").is_file():
                raise FileNotFoundError(
                    f"{manifest}: row {row.name!r} names {folder}, which holds no run.json; export an "
                    "activearena-eval run there with `activearena-report RUN --export-records DIR`"
                )
            for run_spec in expand_specs([str(folder)]):
                run = load_run(run_spec)
                for task, outcomes in run.task_success.items():
                    success[task][run.split] += outcomes
                for ep in run.episodes:
                    if not ep["success"] and ep.get("failure_state") in FAILURES:
                        failures[run.split][ep["failure_state"]] += 1
                        per_task[ep["task"]][run.split][ep["failure_state"]] += 1
        row.success = {t: dict(s) for t, s in success.items()}
        row.failures = dict(failures)
        row.task_failures = {t: {sp: dict(c) for sp, c in v.items()} for t, v in per_task.items()}
        rows.append(row)
    return spec, rows


def _fmt(p: float) -> str:
    return f"{p:.0f}" if abs(p - round(p)) < 0.05 else f"{p:.1f}"


def _pct(outcomes: list[bool]) -> str:
    return _fmt(100.0 * sum(outcomes) / len(outcomes)) if outcomes else "-"


def _cell(row: Row, task: str) -> str:
    splits = row.success.get(task)
    if not splits:
        return "-"
    return f"{_pct(splits.get('id', []))} / {_pct(splits.get('ood', []))}"


def _all_tasks(row: Row, n_tasks: int) -> str:
    """Task-macro mean over every registered task, only where the row covers them all."""
    if len(row.success) < n_tasks:
        return "-"
    out = []
    for split in ("id", "ood"):
        rates = [100.0 * sum(s[split]) / len(s[split]) for s in row.success.values() if s.get(split)]
        out.append(_fmt(sum(rates) / len(rates)) if len(rates) == n_tasks else "-")
    return " / ".join(out)


def _short(task: str) -> str:
    return task.removesuffix("_rotate_view").removesuffix("_press_button")


def leaderboard_table(spec: dict, rows: list[Row], n_tasks: int) -> str:
    """The front page's table: success % ID / OOD per featured task, and over all tasks."""
    tasks = spec["tasks"]
    head = ["policy", "memory", *[f"`{_short(t)}` ID / OOD" for t in tasks], f"all {n_tasks} tasks ID / OOD"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for row in (r for r in rows if r.leaderboard):
        cells = [row.policy, row.memory or "-"]
        cells += [_cell(row, t) for t in tasks] + [_all_tasks(row, n_tasks)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _episodes(row: Row) -> str:
    n = {s: sum(len(v.get(s, [])) for v in row.success.values()) for s in ("id", "ood")}
    tasks = f"{len(row.success)} tasks" if len(row.success) > 1 else "1 task"
    return f"{n['id']:,} ID + {n['ood']:,} OOD episodes, {tasks}"


def rows_section(spec: dict, rows: list[Row], records_link: str) -> str:
    """Per row: scores per task, failure states, data, training, hardware, records and commands."""
    out = []
    for row in rows:
        out.append(f"### {row.policy}\n")
        if row.note:
            out.append(row.note + "\n")
        scores = ", ".join(f"`{_short(t)}` {_cell(row, t)}" for t in sorted(row.success))
        if len(row.success) > 6:
            scores = f"per task {_cell_range(row)}, all tasks {_all_tasks(row, len(row.success))}"
        fails = "; ".join(
            f"{s.upper()} " + " / ".join(str(row.failures.get(s, {}).get(k, 0)) for k in FAILURES)
            for s in ("id", "ood")
        )
        out.append(f"- **Success % (ID / OOD)**: {scores} ({_episodes(row)})")
        out.append(f"- **Failures (DM / CO / CR)**: {fails}")
        out.append(f"- **Data**: {row.data}")
        out.append(f"- **Training**: {row.training}")
        out.append(f"- **Hardware**: {row.hardware}")
        links = ", ".join(f"[`{r}`]({records_link}/{r})" for r in row.records)
        out.append(f"- **Records**: {links}\n")
        out.append("```bash\n" + "\n".join(row.commands) + "\n```\n")
    return "\n".join(out).rstrip() + "\n"


def _cell_range(row: Row) -> str:
    """For a row over many tasks: the range of per-task success, ID and OOD."""
    parts = []
    for split in ("id", "ood"):
        rates = [100.0 * sum(s[split]) / len(s[split]) for s in row.success.values() if s.get(split)]
        lo, hi = min(rates), max(rates)
        parts.append(f"{lo:.0f}" if lo == hi else f"{lo:.0f}-{hi:.0f}")
    return " / ".join(parts)


def comparison_cells(
    spec: dict, rows: list[Row], names: list[str] | None = None
) -> tuple[list[str], list[list[str]]]:
    """The manifest's ``comparison``: the named rows (``names``, default all of the comparison's) side by
    side on its ``tasks``, ID / OOD success per task, the ID failures by state and the training (the
    memory comparison: the same policy with and without memory); "-" where a row was not evaluated on
    a task."""
    comp = spec.get("comparison")
    if not comp:
        raise ValueError("the manifest has no 'comparison' (its 'tasks' and 'rows')")
    tasks, by_name = comp["tasks"], {r.name: r for r in rows}
    names = list(comp["rows"] if names is None else names)
    missing = [n for n in names if n not in by_name]
    if missing:
        raise ValueError(
            f"the manifest's comparison names rows it does not hold: {missing} (its rows: {sorted(by_name)})"
        )
    head = ["policy", "memory", *[f"`{_short(t)}` ID / OOD" for t in tasks]]
    head += ["ID failures DM / CO / CR", "training"]
    cells = []
    for name in names:
        row = by_name[name]
        fails = []
        for task in (t for t in tasks if t in row.success):
            counts = row.task_failures.get(task, {}).get("id", dict.fromkeys(FAILURES, 0))
            fails.append(f"`{_short(task)}` " + " / ".join(str(counts[k]) for k in FAILURES))
        cells.append(
            [
                row.policy,
                row.memory or "-",
                *[_cell(row, t) for t in tasks],
                "; ".join(fails) or "-",
                row.training,
            ]
        )
    return head, cells


def comparison_table(spec: dict, rows: list[Row]) -> str:
    """The comparison as the results page's Markdown table."""
    head, cells = comparison_cells(spec, rows)
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(c) + " |" for c in cells]
    return "\n".join(lines)


def comparison_picture(manifest: Path, spec: dict) -> tuple[Path, str] | None:
    """The picture the comparison names (``comparison.picture``: a path relative to the manifest and a
    caption), or None; a clear error if it names a file that is not there."""
    pic = spec.get("comparison", {}).get("picture")
    if not pic:
        return None
    path = (manifest.parent / pic["path"]).resolve()
    if not path.is_file():
        raise FileNotFoundError(f"{manifest}: comparison.picture names {path}, which does not exist")
    return path, pic.get("caption", "")


def comparison_report(manifest: Path, names: list[str] | None = None) -> tuple[list[str], dict]:
    """What ``activearena-report --comparison`` shows: the run specs of the rows' records (labelled by
    row name) and the comparison itself (its table, picture, and each row's hardware and commands)."""
    spec, rows = load_rows(manifest)
    head, cells = comparison_cells(spec, rows, names)
    records_dir = manifest.parent / spec.get("records_dir", "records")
    by_name = {r.name: r for r in rows}
    chosen = [by_name[n] for n in (spec["comparison"]["rows"] if names is None else names)]
    specs = [f"{row.name}={records_dir / record}" for row in chosen for record in row.records]
    info = {
        "table": (head, cells),
        "picture": comparison_picture(manifest, spec),
        "commands": [(row.policy, row.hardware, row.commands) for row in chosen],
    }
    return specs, info


def replace_block(text: str, name: str, content: str, where: str = "page") -> str:
    """``text`` with the block between the ``generated:name`` markers replaced by ``content``."""
    pattern = re.compile(
        rf"(<!-- generated:{re.escape(name)} -->\n)(.*?)(<!-- /generated:{re.escape(name)} -->)", re.S
    )
    if not pattern.search(text):
        raise ValueError(
            f"{where} has no '<!-- generated:{name} -->' ... '<!-- /generated:{name} -->' block; "
            "add the two markers where the generated text belongs"
        )
    return pattern.sub(lambda m: m.group(1) + content.rstrip("\n") + "\n" + m.group(3), text, count=1)


def render_pages(manifest: Path, pages: list[Path], n_tasks: int) -> dict[Path, str]:
    """The new text of each page: its leaderboard block and, where it has one, its rows block (record
    links relative to the page)."""
    spec, rows = load_rows(manifest)
    table = leaderboard_table(spec, rows, n_tasks)
    records_dir = (manifest.parent / spec.get("records_dir", "records")).resolve()
    out = {}
    for page in pages:
        text = replace_block(page.read_text(), "leaderboard", table, str(page))
        if "<!-- generated:comparison -->" in text:
            text = replace_block(text, "comparison", comparison_table(spec, rows), str(page))
        if "<!-- generated:rows -->" in text:
            link = Path(os.path.relpath(records_dir, page.resolve().parent)).as_posix()
            text = replace_block(text, "rows", rows_section(spec, rows, link), str(page))
        out[page] = text
    return out
