#!/usr/bin/env bash
# The inspection memory pair of docs/results.md from nothing, resumable: build the 900-episode
# check_block_color recipe, ground the vision tower, train the chunk-12 and memory-free presets
# (configs/policy/small/oft_decision_{action_12,no_0}_ws_inspection.json), draw their validation
# curves, choose the chunk-12 run's best checkpoint on validation (manifest ID 50-99; the latest of a
# tie), score both runs at that step on the protocol and the chunk-12 one with its memory blanked, and
# write the report of the three. About 11 h on 2 CPU cores (estimated from the stages' times in
# docs/results.md: 8 h of it training). Killed at any point, the same command goes on where it
# stopped: the build and the evaluations resume, training resumes from its last checkpoint, a
# finished stage is skipped (its folder holds .done).
#   bash scripts/inspection_pair.sh                       # everything under outputs/
#   OUT=/data/pair bash scripts/inspection_pair.sh         # elsewhere
# Another chunk-12 preset against the same memory-free run, e.g. the span-read memory:
#   CHUNK_PRESET=oft_decision_action_12_ws_inspection_span CHUNK_RUN=inspection_action_12_span bash scripts/inspection_pair.sh
# Smaller, to try the pipeline (every stage, minutes): EPISODES=3 GROUND_EPISODES=0-2 GROUND_EPOCHS=1
#   STEPS=2 BATCH=2 SAVE_FREQ=1 VAL_EPISODES=1 PROTOCOL_EPISODES=1 OUT=/tmp/pair bash scripts/inspection_pair.sh
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bootstrap.sh"
cd "$ROOT"
OUT="${OUT:-outputs}"
EPISODES="${EPISODES:-900}"
GROUND_EPISODES="${GROUND_EPISODES:-0-269}"
GROUND_EPOCHS="${GROUND_EPOCHS:-2}"
STEPS="${STEPS:-8000}"
BATCH="${BATCH:-64}"
SAVE_FREQ="${SAVE_FREQ:-500}"
VAL_EPISODES="${VAL_EPISODES:-50}"
PROTOCOL_EPISODES="${PROTOCOL_EPISODES:-50}"
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}" OMP_WAIT_POLICY=PASSIVE HF_HUB_OFFLINE=1
CHUNK_PRESET="${CHUNK_PRESET:-oft_decision_action_12_ws_inspection}"
CHUNK_RUN="${CHUNK_RUN:-inspection_action_12}"
REPO=local/cpu_inspection
BUILD="$OUT/datasets/cpu_inspection"
SLIM="$OUT/datasets/cpu_inspection_vla"
VLM="$OUT/small_vlm_v256d4_p32"
GROUNDED="$OUT/small_vlm_v256d4_p32_grounded_inspection"
CACHE="$OUT/vision_cache/cpu_inspection_grounded.safetensors"
SIZE=(--env.observation_height=192 --env.observation_width=256)

say() { echo "[inspection_pair] $*" >&2; }

# once DIR holds .done the stage is skipped; an unfinished DIR is replaced (--overwrite)
stage() {
  local dir="$1"; shift
  if [ -f "$dir/.done" ]; then say "done: $dir"; return; fi
  say "running: $*"
  "$@" $( [ -e "$dir" ] && echo --overwrite ) && touch "$dir/.done"
}

say "1/7 the build ($EPISODES episodes; resumes)"
activearena-build-dataset --recipe datasets_build/cpu_inspection.json --repo-id "$REPO" --root "$BUILD" \
  --episodes "$EPISODES" --workers 2
say "2/7 the slim copy, the backbone, its grounded tower and the tower's table"
stage "$SLIM" activearena-slim-dataset --root "$BUILD" --out "$SLIM" --repo-id "$REPO" --vla
stage "$VLM" activearena-make-tiny-vlm "$VLM" --hidden 128 --layers 4 --vision-hidden 256 --vision-depth 4 --patch 32
stage "$GROUNDED" activearena-ground-vision "$VLM" --root "$BUILD" --out "$GROUNDED" --image-max-pixels 49152 \
  --point-weight 1 --search-weight 1 --identity-weight 1 --reading-window 6 --episodes "$GROUND_EPISODES" \
  --epochs "$GROUND_EPOCHS"
mkdir -p "$(dirname "$CACHE")"
if [ ! -f "$CACHE.done" ]; then
  activearena-cache-vision "$GROUNDED" --root "$SLIM" --repo-id "$REPO" --image-max-pixels 49152 --out "$CACHE" \
    $( [ -e "$CACHE" ] && echo --overwrite ) && touch "$CACHE.done"
fi

last_step() {  # the step of a run's last checkpoint, 0 if none
  local f="$1/checkpoints/last/training_state/training_step.json"
  [ -f "$f" ] && python -c "import json,sys; print(json.load(open(sys.argv[1]))['step'])" "$f" || echo 0
}

train() {  # train RUN PRESET: from the start, from its last checkpoint, or not at all once it is done
  local run="$OUT/train/$1" preset="configs/policy/small/$2.json" step
  step="$(last_step "$run")"
  if [ "$step" -ge "$STEPS" ]; then say "done: $run (step $step)"; return; fi
  if [ "$step" -gt 0 ]; then
    say "resuming $run from step $step"
    lerobot-train --config_path="$run/checkpoints/last/pretrained_model/train_config.json" --resume=true
  else
    say "training $run"
    rm -rf "$run"  # nothing saved yet: lerobot-train refuses an existing output_dir
    lerobot-train --config_path="$preset" --dataset.repo_id="$REPO" --dataset.root="$SLIM" --output_dir="$run" \
      --policy.vlm_path="$GROUNDED" $( [ "$1" = "$CHUNK_RUN" ] && echo --policy.vision_cache="$CACHE" ) \
      --steps="$STEPS" --policy.scheduler_decay_steps="$STEPS" --batch_size="$BATCH" --save_freq="$SAVE_FREQ"
  fi
}
say "3/7 training the chunk-12 run"
train "$CHUNK_RUN" "$CHUNK_PRESET"
say "4/7 training the memory-free run"
train inspection_no_0 oft_decision_no_0_ws_inspection

say "5/7 validation curves (manifest ID 50-99, every other checkpoint; resumes)"
for run in "$CHUNK_RUN" inspection_no_0; do
  activearena-learning-curve "$OUT/train/$run" --task check_block_color --validation --episodes "$VAL_EPISODES" \
    --every 2 --out "$OUT/curves/$run"
done
activearena-learning-curve --overlay "chunk-12=$OUT/curves/$CHUNK_RUN" "memory-free=$OUT/curves/inspection_no_0" \
  --title "check_block_color: $CHUNK_RUN and inspection_no_0, validation by step" --out "$OUT/curves/$CHUNK_RUN.png"
STEP="$(python -c "import sys; from lerobot_activearena.eval.learning_curve import best_checkpoint, read_curve
print(best_checkpoint(read_curve(sys.argv[1]))['step'])" "$OUT/curves/$CHUNK_RUN")"
CKPT="$(printf '%06d' "$STEP")"
say "the chunk-12 run's checkpoint on validation: step $STEP; both runs are scored there"

say "6/7 the protocol ($PROTOCOL_EPISODES ID + $PROTOCOL_EPISODES OOD; resumes), and the chunk-12 run blanked (ID)"
for run in "$CHUNK_RUN" inspection_no_0; do
  activearena-eval --policy.path="$OUT/train/$run/checkpoints/$CKPT/pretrained_model" --policy.device=cpu "${SIZE[@]}" \
    --tasks=check_block_color --episodes "$PROTOCOL_EPISODES" --workers 2 --label "$run" --out "$OUT/protocol/$run"
done
activearena-eval --policy.path="$OUT/train/$CHUNK_RUN/checkpoints/$CKPT/pretrained_model" \
  --policy.memory_ablation=blank --splits id --policy.device=cpu "${SIZE[@]}" --tasks=check_block_color \
  --episodes "$PROTOCOL_EPISODES" --workers 2 --label "${CHUNK_RUN}_blank" --out "$OUT/protocol/${CHUNK_RUN}_blank"

say "7/7 the report"
activearena-report "$OUT/protocol/$CHUNK_RUN" "$OUT/protocol/${CHUNK_RUN}_blank" \
  "$OUT/protocol/inspection_no_0" --out "$OUT/report/$CHUNK_RUN"
say "done: $OUT/report/$CHUNK_RUN/report.html, curves in $OUT/curves/"
