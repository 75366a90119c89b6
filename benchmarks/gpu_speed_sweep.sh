#!/usr/bin/env bash
# The 2B training step on one GPU for every gradient-checkpointing choice, compiled blocks first, then
# eager on the same machine as the baseline (docs/policy.md's tables). Random weights at the 2B size,
# batch 7, K = 12, the usual and the all-valid batch. At most 8.5 min: the compiled sweep is stopped
# after 330 s, the eager one after 150 s.
#   on the GPU machine (../shared/gpu kit): source .gpu/setup.sh && OUT=DIR bash benchmarks/gpu_speed_sweep.sh
#   CPU dry run (tiny model, batch 2, 1 step): DRYRUN=1 OUT=/tmp/sweep bash benchmarks/gpu_speed_sweep.sh
# LANGUAGE_LAYERS: the extra row, vision tower + the first N language layers (activation_memory.py
# prints the N that fits a budget). STEPS and WARMUP: timed and untimed steps per row (2, 1); ONLY=0:
# the compiled sweep alone.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
OUT="${OUT:-outputs/gpu_speed_sweep}"
N="${LANGUAGE_LAYERS:-12}"
PY="${PYTHON:-python3}"
mkdir -p "$OUT"
VLM="${VLM:-/tmp/aa_qwen3_vl_2b_random}"
if [ "${DRYRUN:-0}" = "1" ]; then
  ARGS=(--device cpu --batch-size 2 --history 2 --steps 1 --warmup 1)
  VLM_ARGS=()
  N=1
  LIMIT_S=(1200 1200)
else
  LIMIT_S=("${COMPILED_TIMEOUT_S:-330}" "${EAGER_TIMEOUT_S:-150}")
  ARGS=(--device cuda --batch-size 7 --history 12 --steps "${STEPS:-2}" --warmup "${WARMUP:-1}")
  VLM_ARGS=(--architecture qwen3-vl-2b)
fi
[ -d "$VLM" ] || "$PY" -m lerobot_activearena.cli.make_tiny_vlm "$VLM" "${VLM_ARGS[@]}" >"$OUT/vlm.log" 2>&1
for i in ${ONLY:-0 1}; do
  compile=$([ "$i" = 0 ] && echo all || echo none)
  log="$OUT/sweep_compile_${compile}.log"
  timeout -k 5 "${LIMIT_S[$i]}" "$PY" benchmarks/oft_train_step.py --synthetic --sweep --vlm-path "$VLM" \
    "${ARGS[@]}" --compile-layers "$compile" --checkpoint-language-layers "$N" >"$log" 2>&1
  echo "compile_layers=$compile: rc=$? ($log)"
  grep "^checkpointing" "$log"
done
