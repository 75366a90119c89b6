"""The benchmark's validity suite: every (task, split, adversary) is a shard of episodes on seeds
outside the evaluation manifests, run on the same engine as ``activearena-eval`` (datatrove: local
processes or Slurm array jobs with a dependent report job). Each finished episode is appended to its
shard's record file at once; re-running the same command resumes (finished episodes are kept, a line
cut by a kill is dropped, errors are retried). The summary checks each row against its target.

Run folder::

    records/<task>__<split>__<adversary>.jsonl   one line per finished episode
    logs/                                        datatrove logs and completions
    validity.md, validity.csv                   the table
"""

from __future__ import annotations

import collections
import csv
import json
import re
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from datatrove.pipeline.base import PipelineStep
from tqdm import tqdm

from ..sharding import ProgressBars, one_core, run_local, submit_slurm
from .adversaries import ADVERSARIES, check_outside_manifests, get_adversary, run_episode, validity_seeds

REASON_CHARS = 80
RECORDS = "records"

Shard = tuple[str, str, str]  # (task, split, adversary)


def _key(rec: dict) -> tuple:
    return rec["task"], rec["split"], rec["adversary"], int(rec["seed"])


def records_path(out_dir: Path, shard: Shard) -> Path:
    return Path(out_dir) / RECORDS / ("__".join(shard) + ".jsonl")


def play(task: str, split: str, adversary: str, seed: int) -> dict:
    """One episode; an exception is recorded (``error``), not raised; a resumed run retries it."""
    t0 = time.perf_counter()
    try:
        return run_episode(task, split, adversary, seed)
    except Exception as exc:
        return {
            "task": task,
            "split": split,
            "adversary": adversary,
            "seed": int(seed),
            "success": False,
            "steps": 0,
            "failure_state": "ERR",
            "failure_reason": f"{type(exc).__name__}: {exc}"[:300],
            "seconds": round(time.perf_counter() - t0, 3),
            "error": True,
        }


def load_records(path: Path) -> dict[tuple, dict]:
    """Finished episodes of one record file by key; a line cut by a kill is dropped (and the file
    rewritten without it, so appends start on a fresh line). Errors are not kept."""
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


def load_all_records(out_dir: Path) -> dict[tuple, dict]:
    out: dict[tuple, dict] = {}
    for path in sorted((Path(out_dir) / RECORDS).glob("*.jsonl")):
        out.update(load_records(path))
    return out


class ValidityShardStep(PipelineStep):
    """datatrove step: rank r plays the unfinished episodes of shard r."""

    name = "ActiveArena validity shard"
    type = "VALIDITY"

    def __init__(self, shards: list[Shard], seeds: list[int], out_dir: str, one_thread: bool):
        super().__init__()
        self.shards, self.seeds, self.out_dir, self.one_thread = shards, seeds, out_dir, one_thread

    def run(self, data=None, rank: int = 0, world_size: int = 1):
        if self.one_thread:
            one_core()
        shard = self.shards[rank]
        path = records_path(Path(self.out_dir), shard)
        path.parent.mkdir(parents=True, exist_ok=True)
        done = load_records(path)
        with open(path, "a") as f:
            for seed in self.seeds:
                if (*shard, seed) in done:
                    continue
                rec = play(*shard, seed)
                f.write(json.dumps(rec) + "\n")
                f.flush()
                self.stat_update("errors" if rec.get("error") else "episodes")
        return iter(())


class ReportStep(PipelineStep):
    """datatrove step (one task): the table, as the Slurm job that depends on the shard jobs."""

    name = "ActiveArena validity report"
    type = "REPORT"

    def __init__(self, shards: list[Shard], seeds: list[int], out_dir: str):
        super().__init__()
        self.shards, self.seeds, self.out_dir = shards, seeds, out_dir

    def run(self, data=None, rank: int = 0, world_size: int = 1):
        write_report(summarise(collect(self.shards, self.seeds, Path(self.out_dir))), self.out_dir)
        return iter(())


class _Progress(ProgressBars):
    def __init__(self, out_dir: Path, total: int, before: int):
        super().__init__()
        self.folder = Path(out_dir) / RECORDS
        self.before = before
        self.bar = tqdm(total=total, initial=before, desc="validity episodes", unit="ep")

    def refresh(self) -> None:
        lines = sum(f.read_bytes().count(b"\n") for f in self.folder.glob("*.jsonl"))
        self.bar.update(max(0, min(self.bar.total, lines) - self.bar.n))

    def close(self) -> None:
        self.bar.close()


def collect(shards: Sequence[Shard], seeds: Sequence[int], out_dir: Path) -> list[dict]:
    """The records of every requested episode, in order; a missing or failed one as an ``ERR`` stub."""
    done = load_all_records(out_dir)
    return [done.get((*s, seed)) or _error_stub(*s, seed) for s in shards for seed in seeds]


def run_suite(
    tasks: Sequence[str],
    adversaries: Sequence[str],
    seeds: int | Iterable[int],
    splits: Sequence[str] = ("id",),
    out_dir: str | Path = "outputs/validity",
    workers: int = 2,
    executor: str = "local",
    slurm: dict | None = None,
) -> list[dict] | None:
    """Play every (task, split, adversary, seed) episode not yet recorded under ``out_dir`` and
    return the records of all requested episodes (None when submitted to Slurm: the report job
    writes the table). ``seeds``: a count (seeds VALIDITY_SEED_BASE..) or explicit seeds."""
    for a in adversaries:
        get_adversary(a)
    seeds = validity_seeds(seeds) if isinstance(seeds, int) else [int(s) for s in seeds]
    check_outside_manifests(tasks, seeds)
    out_dir = Path(out_dir).resolve()
    shards = [(t, sp, a) for t in tasks for sp in splits for a in adversaries]
    before = load_all_records(out_dir)
    n_done = sum((*s, seed) in before for s in shards for seed in seeds)
    if n_done:
        print(f"resuming {out_dir}: {n_done} of {len(shards) * len(seeds)} episodes already recorded")
    logs = out_dir / "logs"
    for rank, shard in enumerate(shards):  # datatrove skips completed ranks: only where nothing is missing
        if any((*shard, seed) not in before for seed in seeds):
            (logs / "completions" / f"{rank:05d}").unlink(missing_ok=True)
    workers = max(1, min(workers, len(shards)))
    step = ValidityShardStep(shards, seeds, str(out_dir), one_thread=workers > 1)
    if executor == "slurm":
        submit_slurm(
            step, len(shards), ReportStep(shards, seeds, str(out_dir)), logs, "activearena-validity", slurm
        )
        return None
    if executor != "local":
        raise ValueError(f"executor must be 'local' or 'slurm', got {executor!r}")
    run_local(step, len(shards), workers, logs, _Progress(out_dir, len(shards) * len(seeds), n_done))
    records = collect(shards, seeds, out_dir)
    errors = sum(bool(r.get("error")) for r in records)
    if errors:
        print(
            f"{errors} episode(s) raised an error (see 'ERR' lines under {out_dir / RECORDS}; a re-run retries them)"
        )
    return records


def _error_stub(task: str, split: str, adversary: str, seed: int) -> dict:
    return {
        "task": task,
        "split": split,
        "adversary": adversary,
        "seed": seed,
        "success": False,
        "steps": 0,
        "failure_state": "ERR",
        "failure_reason": "error or not run (see the record files)",
        "seconds": 0.0,
        "error": True,
    }


# ---- summary -------------------------------------------------------------------------------------
def _short_reason(reason: str) -> str:
    """Group reasons that differ only in coordinates; cut long ones."""
    r = re.sub(r"\[[^\]]*\]", "[...]", reason or "").strip()
    return r if len(r) <= REASON_CHARS else r[: REASON_CHARS - 3] + "..."


@dataclass(frozen=True)
class Target:
    """A bound on an adversary's success rate: a ceiling (``at_least=False``; ``free`` successes are
    allowed whatever the rate, for small samples) or, for the expert, a floor."""

    rate: float
    at_least: bool = False
    free: int = 0

    @property
    def text(self) -> str:
        if self.at_least:
            return f">= {self.rate:.0%}"
        if self.free:
            return f"<= {self.free} in {round(self.free / self.rate)} ({self.rate:.0%})"
        return f"<= {self.rate:.0%}"

    def met(self, successes: int, episodes: int) -> bool:
        """A row with no finished episode misses its target."""
        if episodes == 0:
            return False
        if self.at_least:
            return successes >= self.rate * episodes
        return successes <= max(self.free, self.rate * episodes)


LOOK_AT_NOTHING_TARGET = Target(0.02, free=1)  # at most 1 success in 50 episodes
TARGETS = {
    "random": LOOK_AT_NOTHING_TARGET,
    "held_random": LOOK_AT_NOTHING_TARGET,
    "still": LOOK_AT_NOTHING_TARGET,
    "blind_replay": Target(0.10),
    "fixed_view_expert": Target(0.05),
    "expert": Target(0.95, at_least=True),
}


def target(adversary: str) -> Target:
    if adversary not in TARGETS:
        raise ValueError(f"no validity target for adversary {adversary!r}")
    return TARGETS[adversary]


def targets_met(row: dict) -> bool:
    return target(row["adversary"]).met(row["successes"], row["episodes"])


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
        row = {
            "task": task,
            "split": split,
            "adversary": adv,
            "episodes": len(ok),
            "successes": k,
            "success_rate": k / len(ok) if ok else float("nan"),
            "errors": len(rs) - len(ok),
            "failure_states": dict(sorted(states.items())),
            "failure_reasons": reasons.most_common(3),
            "seconds_per_episode": sum(r["seconds"] for r in ok) / max(1, len(ok)),
            "target": target(adv).text,
        }
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


def summary_table(rows: list[dict]) -> str:
    """One line per (task, split), one column per adversary: successes / episodes and the most
    common failure state among the failures (``MISSED`` where the target is not met). The split
    column is left out when every row has the same split."""
    advs = [a for a in ADVERSARIES if any(r["adversary"] == a for r in rows)]
    cells: dict[tuple, dict[str, str]] = collections.defaultdict(dict)
    for r in rows:
        top = max(r["failure_states"].items(), key=lambda kv: kv[1], default=None)
        text = f"{r['successes']}/{r['episodes']}" + (f" ({top[0]} {top[1]})" if top else "")
        cells[(r["task"], r["split"])][r["adversary"]] = text + ("" if r["met"] else " MISSED")
    one_split = len({split for _, split in cells}) == 1
    head = ["task"] + ([] if one_split else ["split"]) + advs
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for (task, split), by_adv in cells.items():
        first = [task] + ([] if one_split else [split])
        lines.append("| " + " | ".join(first + [by_adv.get(a, "-") for a in advs]) + " |")
    return "\n".join(lines)


def write_report(rows: list[dict], out_dir: str | Path) -> str:
    """Write ``validity.md`` (a summary, then the full table) and ``validity.csv`` under ``out_dir``;
    return the full Markdown table."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    table = markdown_table(rows)
    (out_dir / "validity.md").write_text(
        "# ActiveArena validity suite\n\n" + summary_table(rows) + "\n\n## Every row\n\n" + table + "\n"
    )
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
