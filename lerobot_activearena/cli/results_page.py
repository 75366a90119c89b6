"""`activearena-results-page`: write the leaderboard of the README and docs/results.md from the committed
evaluation records that ``docs/results/leaderboard.json`` names (``--check``: fail if a page differs).

    activearena-results-page                 # rewrite the generated blocks of README.md and docs/results.md
    activearena-results-page --check         # what the tests run: the pages match the records
"""

from __future__ import annotations

import argparse
import difflib
import sys
from pathlib import Path


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    p.add_argument("--manifest", type=Path, default=Path("docs/results/leaderboard.json"))
    p.add_argument("--pages", type=Path, nargs="+", default=[Path("README.md"), Path("docs/results.md")])
    p.add_argument("--check", action="store_true", help="write nothing; exit 1 if a page is out of date")
    args = p.parse_args(argv)
    for path in [args.manifest, *args.pages]:
        if not path.is_file():
            p.error(f"{path} not found (run from the repository root, or pass --manifest / --pages)")
    from ..eval.results_page import render_pages
    from ..tasks.registry import task_names

    stale = []
    for page, text in render_pages(args.manifest, args.pages, len(task_names("all"))).items():
        old = page.read_text()
        if old == text:
            continue
        if args.check:
            stale.append(page)
            sys.stdout.writelines(
                difflib.unified_diff(old.splitlines(True), text.splitlines(True), str(page), "generated", n=1)
            )
        else:
            page.write_text(text)
            print(f"wrote {page}")
    if stale:
        print(f"\n{', '.join(map(str, stale))} differ from the records: run activearena-results-page")
        sys.exit(1)


if __name__ == "__main__":
    main()
