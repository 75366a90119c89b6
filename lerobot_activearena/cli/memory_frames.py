"""`activearena-memory-frames`: play one protocol episode with an ActiveArena-VLA checkpoint and draw
what its memory bank held at the episode's last decision (a PNG).

    activearena-memory-frames --policy.path=outputs/train/RUN/checkpoints/last/pretrained_model \\
        --task count_target_press_button --episode-index 0 --out outputs/memory_frames.png
"""

from __future__ import annotations

import argparse
from pathlib import Path


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    p.add_argument("--policy.path", dest="policy_path", type=Path, required=True)
    p.add_argument(
        "--policy.vlm_path", dest="vlm_path", default=None, help="where the backbone is, if it moved"
    )
    p.add_argument("--task", required=True)
    p.add_argument("--split", default="id", choices=["id", "ood"])
    p.add_argument("--episode-index", type=int, default=0, help="manifest index (the protocol: 0-49)")
    p.add_argument("--title", default=None)
    p.add_argument("--out", type=Path, required=True)
    args = p.parse_args(argv)
    if not (args.policy_path / "config.json").is_file():
        p.error(f"{args.policy_path} holds no config.json: pass a checkpoint's pretrained_model folder")
    from ..eval.memory_frames import draw_memory, play_and_record
    from ..tasks import get_task

    try:
        get_task(args.task)
        played = play_and_record(args.policy_path, args.task, args.split, args.episode_index, args.vlm_path)
    except (KeyError, ValueError) as exc:
        p.error(str(exc))
    title = args.title or f"{args.task} {args.split} episode {args.episode_index}"
    print(f"wrote {draw_memory(played, title, args.out)}")


if __name__ == "__main__":
    main()
