#!/usr/bin/env bash
# Main job: sets everything up on a fresh machine, then runs the scripted expert on every task (seed 0,
# ID split by default) and writes outputs/expert/<task>_id_0/{head.mp4,annotations.jsonl,episode.json}.
# Extra arguments go to activearena-expert-video (e.g. --split ood --seed 3 --task IA).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bootstrap.sh"
cd "$ROOT"
activearena-expert-video --task all --out outputs/expert "$@"
