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


def image_size(text: str | tuple[int, int]) -> tuple[int, int]:
    """``"96x128"`` -> (96, 128): the head image's height and width, 3:4."""
    from ..sim.head_camera import validate_head_size

    if isinstance(text, (tuple, list)):
        return validate_head_size(*text)
    try:
        height, width = (int(v) for v in str(text).lower().split("x"))
    except ValueError:
        raise ValueError(f"image size must be HEIGHTxWIDTH, e.g. 96x128; got {text!r}") from None
    return validate_head_size(height, width)
