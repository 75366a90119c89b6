#!/usr/bin/env bash
# Main job: sets everything up on a fresh machine, then runs the ActiveArena protocol with
# activearena-eval on a representative subset: the scripted-expert policy (activearena_expert, no
# weights) on every task, ID and OOD, the first $EPISODES manifest episodes each (the protocol uses
# 50), and the same expert with the view fixed at home (ActiveArena-Fixed); then the leaderboard
# report of both rows side by side in outputs/report/ (report.html, report.md, CSVs, PNGs). Earlier outputs of this job are replaced.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bootstrap.sh"
cd "$ROOT"
EPISODES="${EPISODES:-2}"
WORKERS="${WORKERS:-$(nproc)}"
for run in expert expert_fixed; do
  extra=()
  [ "$run" = expert_fixed ] && extra=(--fixed-view)
  activearena-eval --policy.type=activearena_expert --policy.device=cpu --env.render_pixels=false \
    --episodes "$EPISODES" --workers "$WORKERS" --out "outputs/eval/$run" --overwrite "${extra[@]}" "$@"
done
activearena-report outputs/eval/expert outputs/eval/expert_fixed --out outputs/report
echo "report: outputs/report/report.html (one self-contained page: tables, charts, videos) and report.md"
