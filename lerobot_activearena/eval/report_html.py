"""``report.html``: the leaderboard report as one self-contained page (tables, the PNG charts and the
rollout videos embedded as data URIs), to open in a browser or publish as a single file. Videos past
``inline_video_mb`` are linked (relative to the report folder) instead of embedded."""

from __future__ import annotations

import base64
import html
import io
import re
from pathlib import Path

CSS = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 1200px; color: #222; }
h1 { font-size: 1.6em; } h2 { font-size: 1.25em; margin-top: 1.8em; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.6em 0; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: right; }
th { background: #f1f3f5; text-align: left; } h3 { font-size: 1em; margin: 1.2em 0 0.4em; } td:first-child, th:first-child, td.text { text-align: left; }
img { max-width: 100%; }
.videos { display: grid; grid-template-columns: repeat(auto-fill, minmax(240px, 1fr)); gap: 10px; }
figure { margin: 0; } figcaption { font-size: 0.8em; } video { width: 100%; background: #000; }
p.note { color: #555; font-size: 0.9em; }
"""


def _data_uri(path: Path, mime: str) -> str:
    return f"data:{mime};base64,{base64.b64encode(path.read_bytes()).decode('ascii')}"


def _poster(path: Path) -> str:
    """The video's last frame (where the episode ended) as a JPEG data URI: shown before playing."""
    import av

    frame = None
    try:
        with av.open(str(path)) as container:
            for frame in container.decode(video=0):  # noqa: B007  (the last one is kept)
                pass
    except (av.error.FFmpegError, OSError):  # unreadable here: the browser shows its own placeholder
        return ""
    if frame is None:
        return ""
    buf = io.BytesIO()
    frame.to_image().save(buf, format="JPEG", quality=80)
    return f"data:image/jpeg;base64,{base64.b64encode(buf.getvalue()).decode('ascii')}"


def _code(text: str) -> str:
    """Escaped text with Markdown's `code` spans as <code>."""
    return re.sub(r"`([^`]+)`", r"<code>\1</code>", html.escape(text))


def _table(header: list[str], rows: list[list], fmt) -> str:
    head = "".join(f"<th>{_code(str(h))}</th>" for h in header)
    body = "".join(
        "<tr>"
        + "".join(
            f'<td class="text">{_code(str(x))}</td>' if isinstance(x, str) else f"<td>{fmt(x, h)}</td>"
            for x, h in zip(row, header, strict=True)
        )
        + "</tr>"
        for row in rows
    )
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def write_html(
    out: Path,
    sections: list[tuple[str, str, tuple[list[str], list[list]], str | None]],
    videos: list[tuple[str, str, Path, str]],
    fmt,
    inline_video_mb: float = 64.0,
    commands: list[tuple[str, str, list[str]]] = (),
) -> dict:
    """Write ``out/report.html``. ``sections``: (title, explanation, (header, rows), PNG name in
    ``out`` or None); ``videos``: (task, caption, mp4 path, link relative to ``out``), shown grouped
    by task; ``commands``: (policy, hardware, command lines) of compared rows, each folded under its
    name. Returns how many videos were embedded / linked."""
    parts = ["<h1>ActiveArena leaderboard</h1>"]
    for title, text, (header, rows), png in sections:
        parts += [f"<h2>{html.escape(title)}</h2>", f'<p class="note">{html.escape(text)}</p>']
        parts.append(_table(header, rows, fmt))
        if png and (out / png).is_file():
            parts.append(f'<img alt="{html.escape(title)}" src="{_data_uri(out / png, "image/png")}">')
    if commands:
        parts.append("<h2>How each compared row was made</h2>")
    for policy, hardware, lines in commands:
        parts.append(
            f'<details><summary>{html.escape(policy)}</summary><p class="note">Hardware: '
            f"{html.escape(hardware)}</p><pre>{html.escape(chr(10).join(lines))}</pre></details>"
        )
    budget, embedded, linked = inline_video_mb * 2**20, 0, 0
    by_task: dict[str, list[str]] = {}
    for task, caption, path, link in videos:
        poster = ""
        if path.is_file() and path.stat().st_size <= budget:
            budget -= path.stat().st_size
            src, embedded = _data_uri(path, "video/mp4"), embedded + 1
            poster = f' poster="{_poster(path)}"'
        else:  # over the budget (or missing): a link beside the report
            src, linked = html.escape(link), linked + 1
        by_task.setdefault(task, []).append(
            f'<figure><video controls muted loop preload="metadata" src="{src}"{poster} '
            f'title="{html.escape(path.name)}"></video>'
            f"<figcaption>{html.escape(caption)}: {html.escape(path.name)}</figcaption></figure>"
        )
    parts.append("<h2>Rollout videos</h2>")
    if linked:
        parts.append(
            f'<p class="note">{embedded} videos embedded, {linked} linked (over the '
            f"{inline_video_mb:g} MB embedding budget: activearena-report --inline-video-mb).</p>"
        )
    for task, figures in by_task.items():
        parts += [f"<h3>{html.escape(task)}</h3>", f'<div class="videos">{"".join(figures)}</div>']
    if not by_task:
        parts.append("<p>(none saved)</p>")
    page = (
        '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
        f"<title>ActiveArena leaderboard</title><style>{CSS}</style></head><body>"
        + "\n".join(parts)
        + "</body></html>\n"
    )
    (out / "report.html").write_text(page)
    return {"embedded": embedded, "linked": linked}
