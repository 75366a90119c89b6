"""The README's and docs/results.md's leaderboard are what `activearena-results-page` writes from the
committed records: the pages match, a changed record changes the table, bad manifests are named."""

import json
import shutil
from pathlib import Path

import pytest

from lerobot_activearena.cli.results_page import main as results_page
from lerobot_activearena.eval.results_page import (
    comparison_table,
    leaderboard_table,
    load_rows,
    render_pages,
    replace_block,
)

ROOT = Path(__file__).resolve().parents[2]
MANIFEST = ROOT / "docs" / "results" / "leaderboard.json"


def test_committed_pages_match_the_records(monkeypatch):
    monkeypatch.chdir(ROOT)
    results_page(["--check"])  # exits 1 with a diff when a page is out of date


def _one_row_manifest(tmp_path: Path, record: str) -> Path:
    spec = json.loads(MANIFEST.read_text())
    row = next(r for r in spec["rows"] if record in r["records"])
    spec["rows"] = [dict(row, records=[record])]
    (tmp_path / "records").mkdir()
    shutil.copytree(MANIFEST.parent / "records" / record, tmp_path / "records" / record)
    (tmp_path / "leaderboard.json").write_text(json.dumps(spec))
    return tmp_path / "leaderboard.json"


def test_a_changed_record_changes_the_table(tmp_path):
    record = "act_cpu_count_target_100demos"
    manifest = _one_row_manifest(tmp_path, record)
    spec, rows = load_rows(manifest)
    assert "| 8 / 0 |" in leaderboard_table(spec, rows, 35)  # count: 4 of 50 ID
    info_path = tmp_path / "records" / record / "id" / "eval_info.json"
    info = json.loads(info_path.read_text())
    successes = info["per_task"][0]["metrics"]["successes"]
    first_failure = successes.index(False)
    successes[first_failure] = True  # one more success: 5 of 50
    info_path.write_text(json.dumps(info))
    spec, rows = load_rows(manifest)
    assert "| 10 / 0 |" in leaderboard_table(spec, rows, 35)

    page = tmp_path / "page.md"
    page.write_text("# x\n<!-- generated:leaderboard -->\nold\n<!-- /generated:leaderboard -->\ntail\n")
    text = render_pages(manifest, [page], 35)[page]
    assert "old" not in text and "| 10 / 0 |" in text and text.endswith("tail\n")


def test_bad_manifests_and_pages_are_named(tmp_path):
    manifest = _one_row_manifest(tmp_path, "act_cpu_count_target_100demos")
    spec = json.loads(manifest.read_text())
    spec["rows"][0]["records"] = ["no_such_run"]
    manifest.write_text(json.dumps(spec))
    with pytest.raises(FileNotFoundError, match="no_such_run.*--export-records"):
        load_rows(manifest)
    del spec["rows"][0]["hardware"]
    manifest.write_text(json.dumps(spec))
    with pytest.raises(ValueError, match=r"lacks \['hardware'\]"):
        load_rows(manifest)
    with pytest.raises(ValueError, match="generated:leaderboard"):
        replace_block("no markers here", "leaderboard", "x")


def test_the_comparison_table_reads_the_rows_failures_on_its_tasks(tmp_path):
    manifest = _one_row_manifest(tmp_path, "act_cpu_count_target_100demos")
    spec = json.loads(manifest.read_text())
    name = spec["rows"][0]["name"]
    spec["comparison"] = {"tasks": ["click_bell_rotate_view", "count_target_press_button"], "rows": [name]}
    manifest.write_text(json.dumps(spec))
    spec, rows = load_rows(manifest)
    table = comparison_table(spec, rows).splitlines()
    # 4 of 50 ID solved, 0 OOD; ID failures: 1 DM, 41 CO, 4 CR (the committed episode records)
    assert table[0].split(" | ")[2:4] == ["`click_bell` ID / OOD", "`count_target` ID / OOD"]
    assert table[2].split(" | ")[2:5] == ["-", "8 / 0", "`count_target` 1 / 41 / 4"]  # no bell records
    spec["comparison"]["rows"] = ["nobody"]
    with pytest.raises(ValueError, match="comparison names rows it does not hold"):
        comparison_table(spec, rows)


def test_the_report_opens_with_the_comparison_its_picture_and_each_rows_commands(tmp_path, capsys):
    from lerobot_activearena.cli.report import main as report

    manifest = _one_row_manifest(tmp_path, "act_cpu_count_target_100demos")
    spec = json.loads(manifest.read_text())
    name = spec["rows"][0]["name"]
    (tmp_path / "bank.png").write_bytes((ROOT / "docs" / "img" / "memory_pair_click_bell.png").read_bytes())
    spec["comparison"] = {
        "tasks": ["count_target_press_button"],
        "rows": [name],
        "picture": {"path": "bank.png", "caption": "a memory bank"},
    }
    manifest.write_text(json.dumps(spec))
    out = tmp_path / "report"
    report(["--comparison", str(manifest), "--rows", name, "--out", str(out)])
    md = (out / "report.md").read_text()
    comparison = md.split("## Memory comparison", 1)[1].split("## Success by category")[0]
    row = spec["rows"][0]
    assert (
        f"| {row['policy']} | {row.get('memory') or '-'} | 8 / 0 | `count_target` 1 / 41 / 4 |" in comparison
    )
    assert "![Memory comparison](memory_bank.png)" in comparison and "a memory bank" in comparison
    assert (out / "memory_bank.png").read_bytes() == (tmp_path / "bank.png").read_bytes()
    made = md.split("## How each compared row was made", 1)[1]
    assert spec["rows"][0]["commands"][0] in made and spec["rows"][0]["hardware"] in made
    page = (out / "report.html").read_text()
    assert page.count("<details>") == 1 and "data:image/png;base64," in page
    assert "| 8.0 | 0.0 |" in md  # the row's records feed the report's own tables, under the row's name
    assert f"| {name} |" in md


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--rows", "x"], "give --comparison too"),
        ([], "give run folders to report on, or --comparison"),
        (
            ["--comparison", "MANIFEST", "--rows", "nobody"],
            "comparison names rows it does not hold: ['nobody']",
        ),
        (["--comparison", "MANIFEST", "--picture-missing"], "comparison.picture names"),
    ],
)
def test_the_reports_comparison_refuses_bad_arguments_by_name(tmp_path, capsys, argv, message):
    from lerobot_activearena.cli.report import main as report

    manifest = _one_row_manifest(tmp_path, "act_cpu_count_target_100demos")
    spec = json.loads(manifest.read_text())
    spec["comparison"] = {"tasks": ["count_target_press_button"], "rows": [spec["rows"][0]["name"]]}
    if "--picture-missing" in argv:
        argv = [a for a in argv if a != "--picture-missing"]
        spec["comparison"]["picture"] = {"path": "no_such.png"}
    manifest.write_text(json.dumps(spec))
    argv = [str(manifest) if a == "MANIFEST" else a for a in argv]
    with pytest.raises(SystemExit) as exc:
        report([*argv, "--out", str(tmp_path / "out")])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err
