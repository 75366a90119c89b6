"""analysis/tasks/refresh_expert_notes.py: a build's sidecars get the notes the current expert writes."""

import json
import shutil

import pytest
from helpers.analysis_scripts import load


def test_refresh_checks_the_experts_commands_and_merges_its_notes(bell_count_dataset, tmp_path, monkeypatch):
    """Each episode replayed without rendering must command what the dataset holds; its notes are then
    merged into the build's sidecars and a copy's; a build another expert made is refused untouched."""
    script = load("analysis/tasks/refresh_expert_notes.py")
    root, copy = tmp_path / "build", tmp_path / "copy"
    shutil.copytree(bell_count_dataset, root)
    shutil.copytree(bell_count_dataset, copy)
    sidecars = sorted((root / "meta/activearena/sidecars").glob("*.json"))
    for path in [*sidecars, *sorted((copy / "meta/activearena/sidecars").glob("*.json"))]:
        side = json.loads(path.read_text())
        side["expert_notes"] = {"kept": 1}
        path.write_text(json.dumps(side))
    monkeypatch.setattr("sys.argv", ["refresh", str(root), str(copy)])
    script.main()
    for base in (root, copy):
        for path in sorted((base / "meta/activearena/sidecars").glob("*.json")):
            notes = json.loads(path.read_text())["expert_notes"]
            original = json.loads((bell_count_dataset / path.relative_to(base)).read_text())["expert_notes"]
            assert notes == original | {"kept": 1}
    build = root / "meta/activearena/build.json"
    meta = json.loads(build.read_text())
    meta["plan"]["face_jitter"] = 0.15  # another expert: its commands differ
    build.write_text(json.dumps(meta))
    before = sidecars[0].read_text()
    with pytest.raises(SystemExit, match="differ"):
        script.main()
    assert sidecars[0].read_text() == before
