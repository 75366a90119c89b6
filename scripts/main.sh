#!/usr/bin/env bash
# Main job: sets everything up on a fresh machine, then runs the reference rollout (scan + pick and
# shake a can) and writes outputs/rollout/{head.mp4,annotations.jsonl,episode.json}.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bootstrap.sh"
cd "$ROOT"
activearena-rollout --out outputs/rollout "$@"
