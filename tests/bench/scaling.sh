#!/usr/bin/env bash
# Strong and weak scaling of the solver, beside the machine's own ceiling (issue #40).
#
#   tests/bench/scaling.sh [BIN_DIR] [OUT_DIR]
#
# BIN_DIR holds bench_solver and bench_stream (default build/tests/bench); OUT_DIR receives one
# log per run and summary.tsv (default scaling-out). Environment:
#   MPIRUN   the launcher (default mpirun; orterun from ../shared/tools/mpi-bundle.sh elsewhere)
#   CORES    the largest rank count (default: the number of cores)
#   RANKS    the rank counts to run (default: 1 2 4 ... CORES), e.g. "1 16" for a quick comparison
#   BENCH_ARGS  extra bench_solver arguments for every run (e.g. "--balance kind")
#   QUICK=1  small cases and few steps, to check the script on a 2-core machine
#
# Runs, each alone on the machine with one rank per core (--bind-to core):
#   machine   lscpu's cores and threads per core; a STREAM-like triad on 1 and CORES threads
#   strong    2D dam break of ~1M particles, 3D of ~1M, and the 2D case of 88k particles (80k
#             fluid) of the issue, on 1, 2, 4, 8, ... CORES ranks
#   weak      2D dam break with 100k fluid particles per rank, 1 ... CORES ranks
#   tcp       the largest strong 2D run and the largest weak run with --mca btl self,tcp (ranks
#             talk through the loopback network stack, standing in for a cluster's network)
# Every bench_solver run prints time per step, communication share, imbalance, bytes per
# particle and each unit's share of the step; summary.tsv collects them with the efficiency
# t_1 / (n t_n) (strong) or t_1 / t_n (weak).
set -euo pipefail
bin=${1:-build/tests/bench}
out=${2:-scaling-out}
mpirun=${MPIRUN:-mpirun}
cores=${CORES:-$(nproc)}
mkdir -p "$out"
launch=("$mpirun" --oversubscribe --bind-to core --mca btl_vader_single_copy_mechanism none)

if [ "${QUICK:-0}" = 1 ]; then
  big2=20000 big3=20000 small2=5000 weak=5000 s2=10 s3=4 s88=20 sw=10
else
  # 2D: 1M fluid in the 1 x 1 column, ~1.03M with the tank; 3D: 500k fluid, ~1.03M with the
  # tank's three wall layers.
  big2=1000000 big3=500000 small2=80000 weak=100000 s2=20 s3=10 s88=120 sw=30
fi
ranks=()
if [ -n "${RANKS:-}" ]; then
  read -r -a ranks <<<"$RANKS"
else
  for n in 1 2 4 8 16 32 64; do [ "$n" -le "$cores" ] && ranks+=("$n"); done
fi
read -r -a bench_args <<<"${BENCH_ARGS:-}"

{
  echo "== machine"
  lscpu | grep -E '^(Model name|Socket|Core|Thread|CPU\(s\)|NUMA node\(s\)|L3)' || true
  "$bin/bench_stream" --threads "$cores" --mib 256
} | tee "$out/machine.txt"

printf 'series\tranks\tparticles\tms_per_step\tefficiency\tcommunication_pct\tcommunication_most_waiting_pct\timbalance\tbusy_imbalance\tbytes_per_particle\tunits\n' >"$out/summary.tsv"

# run SERIES RANKS BASE_MS MODE [extra launcher args] -- bench args; prints ms/step.
run() {
  local series=$1 np=$2 base=$3 mode=$4
  shift 4
  local extra=()
  while [ "$1" != -- ]; do extra+=("$1"); shift; done
  shift
  local log="$out/${series}_${np}.log"
  "${launch[@]}" "${extra[@]}" -np "$np" "$bin/bench_solver" --kernel wendland "${bench_args[@]}" "$@" >"$log" 2>&1
  awk -v s="$series" -v np="$np" -v base="$base" -v mode="$mode" '
    /^bench_solver/ { for (i = 1; i <= NF; ++i) if ($i ~ /^particles=/) { split($i, a, "="); n = a[2] } }
    /time\/step/ { t = $2 }
    /memory/ { b = $2 }
    /^  communication/ { c = $2; cs = $9 }
    /^  imbalance/ { im = $2 }
    /^  busy imbalance/ { bi = $3 }
    /^    [a-z_]+ +[0-9.]+ %$/ { u = u sprintf("%s%s %s%%", (u == "" ? "" : ", "), $1, $2) }
    END {
      b0 = (base == "" ? t : base)
      eff = (mode == "strong" ? b0 / (np * t) : b0 / t)
      printf "%s\t%d\t%s\t%.3f\t%.3f\t%s\t%s\t%s\t%s\t%s\t%s\n", s, np, n, t, eff, c, cs, im, bi, b, u
    }' "$log" | tee -a "$out/summary.tsv" | cut -f1-9 >&2
  awk '/time\/step/ { print $2 }' "$log"
}

series() {  # series NAME MODE STEPS bench-args...
  local name=$1 mode=$2 steps=$3
  shift 3
  local base="" t
  for np in "${ranks[@]}"; do
    if [ "$mode" = weak ]; then
      t=$(run "$name" "$np" "$base" weak -- --dim 2 --particles $((weak * np)) --steps "$steps")
    else
      t=$(run "$name" "$np" "$base" strong -- "$@" --steps "$steps")
    fi
    [ -z "$base" ] && base=$t
  done
  echo "$base"
}

echo "== strong and weak scaling (summary.tsv)" >&2
base2=$(series strong_2d_1M strong "$s2" --dim 2 --particles "$big2")
series strong_3d_1M strong "$s3" --dim 3 --particles "$big3" >/dev/null
series strong_2d_88k strong "$s88" --dim 2 --particles "$small2" >/dev/null
baseweak=$(series weak_2d_100k weak "$sw")
top=${ranks[-1]}
run tcp_strong_2d_1M "$top" "$base2" strong --mca btl self,tcp -- --dim 2 --particles "$big2" \
  --steps "$s2" >/dev/null
run tcp_weak_2d_100k "$top" "$baseweak" weak --mca btl self,tcp -- --dim 2 \
  --particles $((weak * top)) --steps "$sw" >/dev/null
column -t -s $'\t' <(cut -f1-10 "$out/summary.tsv")
