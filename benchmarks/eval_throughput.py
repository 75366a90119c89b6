"""Evaluation throughput of the oracle policy through the real lerobot-eval, with 1 and 2 env workers.

    python benchmarks/eval_throughput.py --task SS,MD --episodes 4

Runs `lerobot-eval --policy.type=activearena_expert --env.expert_channel=true` once per worker count
(batch size = workers; async envs when > 1) and prints episodes/hour from LeRobot's own eval timing
(eval_s) and from wall time (including start-up).
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def run(task: str, episodes: int, workers: int, split: str) -> dict:
    exe = shutil.which("lerobot-eval", path=str(Path(sys.executable).parent)) or "lerobot-eval"
    out = Path(tempfile.mkdtemp(prefix="aa_eval_"))
    cmd = [exe, "--policy.type=activearena_expert", "--env.type=activearena", f"--env.task={task}",
           f"--env.split={split}", "--env.expert_channel=true", f"--eval.n_episodes={episodes}",
           f"--eval.batch_size={workers}", f"--eval.use_async_envs={'true' if workers > 1 else 'false'}",
           "--policy.device=cpu", f"--output_dir={out / 'eval'}"]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise SystemExit(p.stderr[-3000:])
    info = json.loads((out / "eval" / "eval_info.json").read_text())
    shutil.rmtree(out, ignore_errors=True)
    n = info["overall"]["n_episodes"]
    return {"workers": workers, "episodes": n, "success": info["overall"]["pc_success"],
            "eval_s": info["overall"]["eval_s"], "wall_s": wall}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--task", default="SS,MD")
    p.add_argument("--episodes", type=int, default=4, help="episodes per task")
    p.add_argument("--split", default="id")
    p.add_argument("--workers", default="1,2")
    args = p.parse_args()
    print("| env workers | episodes | success % | eval s | episodes/hour (eval) | episodes/hour (wall) |")
    print("|---|---|---|---|---|---|")
    for w in [int(x) for x in args.workers.split(",")]:
        r = run(args.task, args.episodes, w, args.split)
        print(f"| {w} | {r['episodes']} | {r['success']:.0f} | {r['eval_s']:.0f} | "
              f"{3600 * r['episodes'] / r['eval_s']:.0f} | {3600 * r['episodes'] / r['wall_s']:.0f} |")


if __name__ == "__main__":
    main()
