"""Argument types shared by the command-line tools."""

from __future__ import annotations


def int_ranges(text: str) -> list[int]:
    """``"0-9,42"`` -> [0, 1, ..., 9, 42] (seeds, episode indices)."""
    out: list[int] = []
    for part in [p.strip() for p in text.split(",") if p.strip()]:
        if "-" in part[1:]:
            a, b = part.split("-", 1)
            out += list(range(int(a), int(b) + 1))
        else:
            out.append(int(part))
    return out
