"""Task lookup by paper name or category. Every module in ``tasks/inventory/`` is imported on first
use; defining a ``Task`` subclass there registers it (no list to edit)."""

from __future__ import annotations

import importlib
import pkgutil

from . import inventory
from .base import CATEGORIES, TASKS, Task

_LOADED = False


def _load() -> None:
    global _LOADED
    if not _LOADED:
        for mod in pkgutil.iter_modules(inventory.__path__):
            if not mod.name.startswith("_"):
                importlib.import_module(f"{inventory.__name__}.{mod.name}")
        _LOADED = True


def get_task(name: str) -> Task:
    _load()
    if name not in TASKS:
        raise ValueError(f"unknown ActiveArena task {name!r}; available: {sorted(TASKS)}")
    return TASKS[name]()


def task_texts() -> list[str]:
    """Every task's instruction, subtask texts and spoken name (a tokenizer's corpus)."""
    out = []
    for name in task_names("all"):
        task = get_task(name)
        out += [*task.instruction_texts(), *(s.text for s in task.subtasks), name.replace("_", " ")]
    return out


def task_names(selector: str = "all") -> list[str]:
    """Resolve 'all', a category (SS/SL/ML/MD/IA), a task name, or a comma list of those."""
    _load()
    out: list[str] = []
    for part in [p.strip() for p in selector.split(",") if p.strip()]:
        if part == "all":
            names = sorted(TASKS)
        elif part in CATEGORIES:
            names = sorted(n for n, t in TASKS.items() if t.category == part)
        elif part in TASKS:
            names = [part]
        else:
            raise ValueError(
                f"unknown task selector {part!r}: use 'all', a category {sorted(CATEGORIES)}, "
                f"or a task name {sorted(TASKS)}"
            )
        out += [n for n in names if n not in out]
    if not out:
        raise ValueError(f"task selector {selector!r} selects no task")
    return out
