"""The front page and the docs as a user meets them: every link and referenced path exists, the
README's Python example runs and prints what it says, and (slow) its quick start runs end to end."""

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [
    ROOT / "README.md",
    *sorted((ROOT / "docs").glob("*.md")),
    ROOT / "benchmarks" / "README.md",
    ROOT / "analysis" / "README.md",
    ROOT / "configs" / "README.md",
    ROOT / "datasets_build" / "README.md",
]
LINK = re.compile(r"\]\(([^)\s]+)\)|src=\"([^\"]+)\"")
REPO_PATH = re.compile(
    r"`((?:docs|configs|benchmarks|analysis|datasets_build|scripts|tests|lerobot_activearena)/[^`\s]*)`"
)


def _code_block(text: str, heading: str, lang: str) -> str:
    section = text.split(f"\n## {heading}\n", 1)[1].split("\n## ", 1)[0]
    return re.search(rf"```{lang}\n(.*?)```", section, re.S).group(1)


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_links_and_paths_resolve(page):
    text = page.read_text()
    missing = []
    for m in LINK.finditer(text):
        target = (m.group(1) or m.group(2)).split("#")[0]
        if target and not re.match(r"[a-z]+://", target) and not (page.parent / target).exists():
            missing.append(target)
    for m in REPO_PATH.finditer(text):
        path, _, test = m.group(1).rstrip(".,:;").partition("::")  # a pytest node id names a test too
        if re.search(r"[<>*{}$]|NAME|\.\.\.", path):
            continue
        if not (ROOT / path).exists():
            missing.append(path)
        elif test and f"def {test.split('::')[-1].split('[')[0]}(" not in (ROOT / path).read_text():
            missing.append(m.group(1))
    assert not missing, f"{page.relative_to(ROOT)} names paths that do not exist: {missing}"


def test_readme_python_example_prints_what_it_says(tmp_path):
    code = _code_block((ROOT / "README.md").read_text(), "Quick start", "python")
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, check=True, timeout=600
    ).stdout.splitlines()
    assert out[0] == "137 (384, 512, 3) (18,)"
    assert out[1] == "Press the bell's top center using the left arm."
    success, state = out[2].split()[:2]
    assert success == "False" and state in ("DM", "CO", "CR")  # random targets never press the bell


# The quick start at a smoke size: the same commands, outputs in a temporary folder, and flags that
# make each one small (argparse and draccus take the last value of a repeated flag).
SMOKE = {
    "activearena-eval": ["--episodes", "1"],
    "activearena-build-dataset": ["--episodes", "1", "--workers", "1"],
    "lerobot-train": ["--steps=2", "--save_freq=2", "--batch_size=2", "--num_workers=0", "--log_freq=1"],
    "activearena-report": [],
}


@pytest.mark.slow
def test_readme_quick_start_runs(tmp_path):
    block = _code_block((ROOT / "README.md").read_text(), "Quick start", "bash")
    commands = [c for c in block.replace("\\\n", " ").splitlines() if c.strip() and not c.startswith("#")]
    assert len(commands) == 5
    bin_dir = Path(sys.executable).parent
    for command in commands:
        argv = shlex.split(command.replace("outputs/", f"{tmp_path}/outputs/"))
        env = dict(os.environ)
        while "=" in argv[0]:  # leading VAR=value assignments
            key, value = argv.pop(0).split("=", 1)
            env[key] = value
        exe = Path(argv[0]).name
        argv = [str(bin_dir / exe), *argv[1:], *SMOKE[exe]]
        done = subprocess.run(argv, cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800)
        assert done.returncode == 0, f"{command}\n{done.stderr[-3000:]}"
    assert (tmp_path / "outputs/report/quickstart/report.html").is_file()
