"""A stand-in for Slurm (sbatch, srun, scontrol) on PATH, so datatrove's Slurm executor can be tested
here: sbatch logs each submission and runs the job's array tasks at once, in order."""

import json
import os
import sys
from pathlib import Path

FAKE_SBATCH = r'''#!/usr/bin/env python3
"""Stand-in for Slurm's sbatch: logs the submission and runs every array task at once, in order."""
import json, os, pathlib, re, subprocess, sys
log = pathlib.Path(os.environ["FAKE_SLURM_LOG"])
args, script = sys.argv[1:-1], sys.argv[-1]
text = open(script).read()
job = 100 + (len(log.read_text().splitlines()) if log.exists() else 0)
with log.open("a") as f:
    f.write(json.dumps({"job": job, "args": args, "script": text}) + "\n")
m = re.search(r"#SBATCH --array=(\d+)-(\d+)", text)
env = dict(os.environ, SLURM_JOB_ID=str(job), SLURM_NODELIST="localhost", SLURM_NODEID="0")
for a in args:
    if a.startswith("--export="):
        env.update(kv.split("=", 1) for kv in a[len("--export="):].split(",") if "=" in kv)
for i in range(int(m.group(1)), int(m.group(2)) + 1) if m else [None]:
    if i is not None:
        env["SLURM_ARRAY_TASK_ID"] = str(i)
    subprocess.run(["bash", script], env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
print(f"Submitted batch job {job}")
'''


def install_fake_slurm(tmp_path: Path, monkeypatch) -> None:
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "sbatch").write_text(FAKE_SBATCH)
    (bin_dir / "srun").write_text(
        '#!/bin/bash\nwhile [[ "$1" == -* ]]; do [[ "$1" == -n ]] && shift; shift; done\nexec "$@"\n'
    )
    (bin_dir / "scontrol").write_text("#!/bin/bash\necho localhost\n")
    for f in bin_dir.iterdir():
        f.chmod(0o755)
    monkeypatch.setenv("PATH", f"{bin_dir}:{Path(sys.executable).parent}:{os.environ['PATH']}")
    monkeypatch.setenv("FAKE_SLURM_LOG", str(tmp_path / "slurm.jsonl"))


def submitted_jobs(tmp_path: Path) -> list[dict]:
    """The submissions the fake sbatch saw: job id, sbatch arguments, script text."""
    return [json.loads(line) for line in (tmp_path / "slurm.jsonl").read_text().splitlines()]
