"""`scripts/inspection_pair.sh` at a smoke size: every stage runs (build, grounding, both trainings,
validation curves, the checkpoint choice, the protocol, the blanked run, the report), and the same
command again skips what is done."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SMOKE = {
    "EPISODES": "12",
    "GROUND_EPISODES": "0-11",
    "GROUND_EPOCHS": "1",
    "STEPS": "4",
    "BATCH": "2",
    "SAVE_FREQ": "2",
    "VAL_EPISODES": "1",
    "PROTOCOL_EPISODES": "1",
}


def _pipeline(out: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, **SMOKE, "OUT": str(out)}
    cmd = ["bash", "scripts/inspection_pair.sh"]
    return subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=3000)


@pytest.mark.slow
@pytest.mark.timeout(3600)  # two runs of the pipeline: about 7 min together on 2 idle cores
def test_the_inspection_pair_runs_end_to_end_and_a_rerun_skips_what_is_done(tmp_path):
    run = _pipeline(tmp_path)
    assert run.returncode == 0, run.stderr[-3000:]
    for name in ("inspection_action_12", "inspection_no_0"):
        step = json.loads(
            (tmp_path / "train" / name / "checkpoints/last/training_state/training_step.json").read_text()
        )
        assert step["step"] == 4
        assert (tmp_path / "curves" / name / "curve.jsonl").is_file()
    assert "checkpoint on validation: step 4" in run.stderr  # the latest of a tie (one episode: 0 % each)
    blank = json.loads((tmp_path / "protocol/inspection_action_12_blank/run.json").read_text())
    assert blank["splits"] == ["id"]
    assert (tmp_path / "report/inspection_action_12/report.html").is_file()
    assert (tmp_path / "curves/inspection_action_12.png").is_file()

    again = _pipeline(tmp_path)
    assert again.returncode == 0, again.stderr[-3000:]
    for line in (
        "done: " + str(tmp_path / "train/inspection_action_12") + " (step 4)",
        "done: " + str(tmp_path / "small_vlm_v256d4_p32_grounded_inspection"),
    ):
        assert line in again.stderr
    assert f"] training {tmp_path}" not in again.stderr and f"] resuming {tmp_path}" not in again.stderr
    assert f"] training {tmp_path}" in run.stderr  # the first run did train
