#!/usr/bin/env bash
# Strong and weak scaling of the solver on this machine (issue: MPI domain decomposition).
#   strong: the same ~200k-particle 2D and 3D dam breaks on 1 and 2 ranks -> efficiency
#   weak:   ~50k 2D particles per rank on 1, 2 and 4 ranks (oversubscribed where needed)
# Usage: tests/bench/scaling.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
bench=$build/tests/bench/bench_solver
mpirun=(mpirun --oversubscribe --allow-run-as-root --bind-to none --mca btl_vader_single_copy_mechanism none)

step_ms() { awk '/time\/step/ {print $2}'; }

echo "== strong scaling (time per step, efficiency t1 / (n t_n))"
for spec in "2 200000 40" "3 200000 8"; do
  read -r dim n steps <<<"$spec"
  t1=$("${mpirun[@]}" -np 1 "$bench" --dim "$dim" --particles "$n" --steps "$steps" | tee /dev/stderr | step_ms)
  t2=$("${mpirun[@]}" -np 2 "$bench" --dim "$dim" --particles "$n" --steps "$steps" | tee /dev/stderr | step_ms)
  awk -v d="$dim" -v a="$t1" -v b="$t2" 'BEGIN { printf "strong %dD: 1 rank %.1f ms/step, 2 ranks %.1f ms/step, efficiency %.0f%%\n", d, a, b, 100 * a / (2 * b) }'
done

echo "== weak scaling (50k fluid particles per rank, 2D)"
for np in 1 2 4; do
  "${mpirun[@]}" -np "$np" "$bench" --dim 2 --particles $((50000 * np)) --steps 30 |
    awk -v np="$np" '/time\/step/ {t=$2} /communication/ {c=$2} END { printf "weak %d ranks: %.1f ms/step, communication %.1f%% of the step\n", np, t, c }'
done
