"""MP4 writing (PyAV, H.264) and annotation overlays drawn with PIL."""

from __future__ import annotations

from pathlib import Path

import av
import numpy as np
from PIL import Image, ImageDraw

from .action import CONTROL_HZ


class Mp4Writer:
    def __init__(self, path: str | Path, fps: int = CONTROL_HZ, crf: int = 23):
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._container = av.open(str(self.path), mode="w")
        self._stream = self._container.add_stream("libx264", rate=fps)
        self._stream.pix_fmt = "yuv420p"
        self._stream.options = {"crf": str(crf), "preset": "veryfast"}
        self._started = False

    def write(self, frame: np.ndarray) -> None:
        if not self._started:
            self._stream.height, self._stream.width = frame.shape[:2]
            self._started = True
        for packet in self._stream.encode(
            av.VideoFrame.from_ndarray(np.ascontiguousarray(frame), format="rgb24")
        ):
            self._container.mux(packet)

    def close(self) -> None:
        for packet in self._stream.encode():
            self._container.mux(packet)
        self._container.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def draw_annotations(
    frame: np.ndarray, lines: list[str], points: list[tuple[float, float, str]]
) -> np.ndarray:
    """Text lines at the top-left and labelled markers at normalised image points."""
    img = Image.fromarray(frame)
    draw = ImageDraw.Draw(img)
    h, w = frame.shape[:2]
    if lines:
        draw.rectangle([0, 0, w, 12 * len(lines) + 4], fill=(0, 0, 0))
        for i, line in enumerate(lines):
            draw.text((4, 2 + 12 * i), line, fill=(255, 255, 255))
    for u, v, label in points:
        x, y = u * w, v * h
        draw.ellipse([x - 5, y - 5, x + 5, y + 5], outline=(0, 255, 0), width=2)
        draw.text((x + 7, y - 6), label, fill=(0, 255, 0))
    return np.asarray(img)
