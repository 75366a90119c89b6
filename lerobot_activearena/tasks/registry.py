"""Task lookup by paper name or category; importing this module registers every task module."""

from __future__ import annotations

from .base import CATEGORIES, TASKS, Task


def _load() -> None:
    from . import (  # noqa: F401  (each module registers its task)
        blocks_ranking_rgb_rotate_view,
        check_block_color,
        click_bell_rotate_view,
        count_target_press_button,
        place_empty_cup_rotate_view,
    )


def get_task(name: str) -> Task:
    _load()
    if name not in TASKS:
        raise ValueError(f"unknown ActiveArena task {name!r}; available: {sorted(TASKS)}")
    return TASKS[name]()


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
            raise ValueError(f"unknown task selector {part!r}: use 'all', a category {sorted(CATEGORIES)}, "
                             f"or a task name {sorted(TASKS)}")
        out += [n for n in names if n not in out]
    return out
