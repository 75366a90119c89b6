"""A training step of a policy preset against ACT's CPU preset, side by side on the same dataset,
through ``lerobot-train`` itself (loading, preprocessing, forward, backward, AdamW).

    activearena-make-tiny-vlm outputs/small_vlm --hidden 128 --layers 4
    python benchmarks/train_step_vs_act.py --root outputs/datasets/cpu_count --repo-id local/cpu_count \\
        configs/policy/small/oft_subtask_action_12_ws.json configs/policy/small/oft_subtask_no_0_ws.json

Runs each preset and ACT (``configs/policy/baselines/act_cpu.json``) in turn, ``--rounds`` times
interleaved so that the machine's drift falls on all of them, for ``--steps`` steps at ``--batch-size`` (16),
and reads lerobot-train's own per-step figures (``updt_s``: forward + backward + optimizer; ``data_s``:
waiting for the next batch) from its log, the first ``--log-every`` steps dropped as warm-up. Prints the
seconds per step of each and its ratio to ACT's from the same round (the issue's budget: <= 1.5x).
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ACT = "configs/policy/baselines/act_cpu.json"
FIELDS = re.compile(r"updt_s:([0-9.]+).*?data_s:([0-9.]+)")


def step_time(config: str, root: Path, repo_id: str, steps: int, log_every: int, extra: list[str]) -> dict:
    """lerobot-train for ``steps`` steps; mean updt_s and data_s over the log windows after the first."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [
            str(Path(sys.executable).with_name("lerobot-train")),
            f"--config_path={config}",
            f"--dataset.repo_id={repo_id}",
            f"--dataset.root={root}",
            f"--output_dir={tmp}/run",
            f"--steps={steps}",
            f"--log_freq={log_every}",
            f"--save_freq={steps * 10}",
            "--save_checkpoint=false",
            *extra,
        ]
        env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
        out = subprocess.run(cmd, capture_output=True, text=True, env=env, check=False)
    if out.returncode:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{out.stderr[-3000:]}")
    windows = [(float(u), float(d)) for u, d in FIELDS.findall(out.stdout + out.stderr)][1:]
    if not windows:
        raise RuntimeError(f"no step figures in the log of {config}: raise --steps above 2 x --log-every")
    upd = statistics.mean(u for u, _ in windows)
    data = statistics.mean(d for _, d in windows)
    return {"updt_s": upd, "data_s": data, "step_s": upd + data}


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("configs", nargs="+", help="lerobot-train config files to time against ACT's")
    p.add_argument("--root", type=Path, required=True, help="the training dataset")
    p.add_argument("--repo-id", required=True)
    p.add_argument("--steps", type=int, default=60)
    p.add_argument("--log-every", type=int, default=10)
    p.add_argument("--rounds", type=int, default=2)
    p.add_argument("--vlm-path", help="--policy.vlm_path for the VLA presets (default: the preset's)")
    p.add_argument("--batch-size", type=int, default=16, help="every run's batch size (the budget's: 16)")
    p.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="STEM=ARG",
        help="a lerobot-train argument for the preset of that file stem only, e.g. "
        "oft_subtask_action_12_ws_grounded_count_frozen=--policy.vision_cache=FILE",
    )
    args = p.parse_args(argv)
    per_preset: dict[str, list[str]] = {}
    for item in args.set:
        stem, sep, arg = item.partition("=")
        if not sep or not arg.startswith("--"):
            p.error(f"--set takes STEM=--lerobot.train.arg=VALUE, got {item!r}")
        per_preset.setdefault(stem, []).append(arg)
    rows: dict[str, list[dict]] = {c: [] for c in [ACT, *args.configs]}
    for r in range(args.rounds):
        for config in rows:
            extra = [f"--policy.vlm_path={args.vlm_path}"] if args.vlm_path and config != ACT else []
            extra += [f"--batch_size={args.batch_size}", *per_preset.get(Path(config).stem, [])]
            fig = step_time(config, args.root, args.repo_id, args.steps, args.log_every, extra)
            rows[config].append(fig)
            print(
                f"round {r + 1} {Path(config).stem:32s} {fig['step_s']:.3f} s/step "
                f"(updt {fig['updt_s']:.3f} + data {fig['data_s']:.3f})",
                flush=True,
            )
    print(f"\nbatch {args.batch_size}, {args.steps} steps a run, {args.rounds} rounds, dataset {args.root}")
    for config, figs in rows.items():
        step = [f["step_s"] for f in figs]
        ratio = [f["step_s"] / a["step_s"] for f, a in zip(figs, rows[ACT], strict=True)]
        print(
            f"{Path(config).parent.name + '/' + Path(config).stem:45s} {min(step):.3f}-{max(step):.3f} s/step "
            f"({args.batch_size / statistics.median(step):.1f} samples/s)  vs ACT {min(ratio):.2f}-{max(ratio):.2f}x"
        )


if __name__ == "__main__":
    main()
