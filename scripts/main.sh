#!/usr/bin/env bash
# Main job: sets everything up on a fresh machine, then evaluates the scripted-expert policy
# (activearena_expert, no weights) with lerobot-eval on every task, ID and OOD (the first
# $EPISODES manifest episodes per task), and writes the leaderboard report to outputs/report/.
# Earlier outputs of this job (outputs/eval/expert_{id,ood}) are replaced.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bootstrap.sh"
cd "$ROOT"
EPISODES="${EPISODES:-2}"
for split in id ood; do
  run="outputs/eval/expert_${split}"
  [ -e "$run" ] && echo "replacing $run (output of an earlier main job)" && rm -rf "$run"
  lerobot-eval --policy.type=activearena_expert --policy.device=cpu \
    --env.type=activearena --env.task=all --env.split="$split" --env.expert_channel=true \
    --env.episode_log_dir="$run/episodes" \
    --eval.n_episodes="$EPISODES" --eval.batch_size=1 --output_dir="$run" "$@"
done
activearena-report expert=outputs/eval/expert_id expert=outputs/eval/expert_ood --out outputs/report
echo "report: outputs/report/report.md (videos under outputs/eval/expert_*/videos)"
