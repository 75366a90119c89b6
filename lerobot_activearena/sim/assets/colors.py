"""Named colours shared by assets and the tasks that ask for them (blocks, patches, pads, mats)."""

from __future__ import annotations

BLOCK_COLORS = {  # named colours shared by blocks, patches and pads
    "red": (0.85, 0.12, 0.1, 1),
    "green": (0.12, 0.7, 0.2, 1),
    "blue": (0.12, 0.3, 0.85, 1),
    "yellow": (0.95, 0.82, 0.1, 1),
    "purple": (0.55, 0.2, 0.7, 1),
    "orange": (0.95, 0.5, 0.1, 1),
}


GRAY = (0.55, 0.55, 0.56, 1)


NEUTRAL_PAD = (0.95, 0.95, 0.93, 1)


MAT_COLORS = {
    "red": (0.85, 0.15, 0.12),
    "green": (0.15, 0.65, 0.25),
    "blue": (0.15, 0.3, 0.85),
    "yellow": (0.95, 0.85, 0.15),
    "black": (0.08, 0.08, 0.09),
    "silver": (0.75, 0.76, 0.78),
    "cyan": (0.1, 0.8, 0.85),
    "beige": (0.9, 0.82, 0.65),
    "pink": (0.95, 0.55, 0.7),
    "orange": (0.95, 0.5, 0.1),
    "purple": (0.55, 0.25, 0.7),
    "white": (0.96, 0.96, 0.96),
    "magenta": (0.85, 0.15, 0.75),
    "gray": (0.45, 0.45, 0.47),
}


RELEASE_MAT_COLORS = ("red", "green", "blue", "yellow", "cyan", "magenta", "black", "gray")  # stapler, mouse
