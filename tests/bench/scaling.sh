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
#   SERIES   what to run, in this order (default: all of them):
#            machine ceiling strong_2d_1M strong_3d_1M strong_2d_88k weak_2d_100k tcp output
#   STORAGES pair-kernel storages to compare (bench_solver --pair-kernel), run one after the
#            other at each rank count so that the machine's drift hits both alike; series of a
#            storage other than the first are named NAME_STORAGE (default: the case's own)
#   BENCH_ARGS  extra bench_solver arguments for every run (e.g. "--balance kind")
#   QUICK=1  small cases and few steps, to check the script on a 2-core machine
#
# Runs, each alone on the machine with one rank per core (--bind-to core):
#   machine   lscpu's cores and threads per core; a STREAM-like triad on 1 and CORES threads
#   ceiling   one 2D and one 3D dam break on one rank alone, then CORES copies of it at once that
#             never communicate (bench_solver --independent 1): what the cores give when all work
#   strong_*  2D dam break of ~1M particles, 3D of ~1M, and the 2D case of 88k particles (80k
#             fluid) of the issue, on each of RANKS
#   weak_*    2D dam break with 100k fluid particles per rank, on each of RANKS
#   tcp       the largest strong 2D run and the largest weak run with --mca btl self,tcp (ranks
#             talk through the loopback network stack, standing in for a cluster's network)
#   output    the 1M 2D and 3D cases on the largest rank count, timing 3 snapshots and 3
#             checkpoints (their share of a run: bench_solver --output)
# Every bench_solver run prints time per step, communication share, imbalance, bytes per
# particle and each unit's share of the step; summary.tsv collects them with the efficiency
# t_1 / (n t_n) (strong) or t_1 / t_n (weak), against the first rank count run.
set -euo pipefail
bin=${1:-build/tests/bench}
out=${2:-scaling-out}
mpirun=${MPIRUN:-mpirun}
cores=${CORES:-$(nproc)}
mkdir -p "$out"
launch=("$mpirun" --oversubscribe --bind-to core --mca btl_vader_single_copy_mechanism none)
read -r -a series_wanted <<<"${SERIES:-machine ceiling strong_2d_1M strong_3d_1M strong_2d_88k weak_2d_100k tcp output}"
read -r -a storages <<<"${STORAGES:-default}"
wanted() { [[ " ${series_wanted[*]} " == *" $1 "* ]]; }

if [ "${QUICK:-0}" = 1 ]; then
  big2=20000 big3=20000 small2=5000 weak=5000 s2=10 s3=4 s88=20 sw=10 c2=5000 c3=3000 sc=10
else
  # 2D: 1M fluid in the 1 x 1 column, ~1.03M with the tank; 3D: 500k fluid, ~0.85M with the
  # tank's walls. The ceiling's copies hold what a rank of the 1M cases holds at 16 ranks.
  big2=1000000 big3=500000 small2=80000 weak=100000 s2=20 s3=10 s88=120 sw=30
  c2=62500 c3=31250 sc=60
fi
ranks=()
if [ -n "${RANKS:-}" ]; then
  read -r -a ranks <<<"$RANKS"
else
  for n in 1 2 4 8 16 32 64; do [ "$n" -le "$cores" ] && ranks+=("$n"); done
fi
top=${ranks[-1]}
read -r -a bench_args <<<"${BENCH_ARGS:-}"

if wanted machine; then
  {
    echo "== machine"
    lscpu | grep -E '^(Model name|Socket|Core|Thread|CPU\(s\)|NUMA node\(s\)|L3)' || true
    "$bin/bench_stream" --threads "$cores" --mib 256
  } | tee "$out/machine.txt"
fi

summary=$out/summary.tsv
[ -f "$summary" ] ||
  printf 'series\tranks\tparticles\tms_per_step\tefficiency\tcommunication_pct\tcommunication_most_waiting_pct\timbalance\tbusy_imbalance\tbytes_per_particle\tunits\n' >"$summary"

# storage_args STORAGE: the bench_solver arguments that select it.
storage_args() { [ "$1" = default ] || echo "--pair-kernel $1"; }
# name SERIES STORAGE: the series' name for that storage.
name() { if [ "$2" = "${storages[0]}" ]; then echo "$1"; else echo "$1_$2"; fi; }

# run SERIES RANKS BASE_MS MODE [extra launcher args] -- bench args; prints ms/step.
run() {
  local series=$1 np=$2 base=$3 mode=$4
  shift 4
  local extra=()
  while [ "$1" != -- ]; do extra+=("$1"); shift; done
  shift
  local log="$out/${series}_${np}.log"
  # A failed run is reported and the next one goes on: one visit measures everything it can.
  "${launch[@]}" "${extra[@]}" -np "$np" "$bin/bench_solver" --kernel wendland "${bench_args[@]}" \
    "$@" >"$log" 2>&1 || echo "$series on $np ranks failed with status $? ($log)" >&2
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
    }' "$log" | tee -a "$summary" | cut -f1-9 >&2
  awk '/time\/step/ { print $2 }' "$log"
}

# series NAME MODE STEPS bench-args...: every rank count, every storage at each; prints the
# first storage's time on the first rank count.
series() {
  local name=$1 mode=$2 steps=$3
  shift 3
  declare -A base=()
  local np st t args
  for np in "${ranks[@]}"; do
    for st in "${storages[@]}"; do
      read -r -a args <<<"$(storage_args "$st")"
      if [ "$mode" = weak ]; then
        t=$(run "$(name "$name" "$st")" "$np" "${base[$st]:-}" weak -- "${args[@]}" --dim 2 \
          --particles $((weak * np)) --steps "$steps")
      else
        t=$(run "$(name "$name" "$st")" "$np" "${base[$st]:-}" strong -- "${args[@]}" "$@" \
          --steps "$steps")
      fi
      [ -z "${base[$st]:-}" ] && base[$st]=$t
    done
  done
  echo "${base[${storages[0]}]}"
}

if wanted ceiling; then
  echo "== ceiling: one copy alone, then $top copies at once that never communicate" >&2
  for d in 2 3; do
    n=$c2
    [ "$d" = 3 ] && n=$c3
    for np in 1 "$top"; do
      log="$out/ceiling_${d}d_$np.log"
      "${launch[@]}" -np "$np" "$bin/bench_solver" --kernel wendland "${bench_args[@]}" --dim "$d" \
        --particles "$n" --steps "$sc" --independent 1 >"$log" 2>&1 || echo "failed: $log" >&2
      echo "ceiling ${d}D ($n fluid), $np cop$([ "$np" = 1 ] && echo y || echo ies):" \
        "$(grep -E 'time/step|independent copies' "$log" | tail -1)" | tee -a "$out/ceiling.txt" >&2
    done
  done
fi

echo "== strong and weak scaling ($summary)" >&2
base2="" baseweak=""
if wanted strong_2d_1M; then base2=$(series strong_2d_1M strong "$s2" --dim 2 --particles "$big2"); fi
if wanted strong_3d_1M; then series strong_3d_1M strong "$s3" --dim 3 --particles "$big3" >/dev/null; fi
if wanted strong_2d_88k; then series strong_2d_88k strong "$s88" --dim 2 --particles "$small2" >/dev/null; fi
if wanted weak_2d_100k; then baseweak=$(series weak_2d_100k weak "$sw"); fi
if wanted tcp; then
  run tcp_strong_2d_1M "$top" "$base2" strong --mca btl self,tcp -- --dim 2 --particles "$big2" \
    --steps "$s2" >/dev/null
  run tcp_weak_2d_100k "$top" "$baseweak" weak --mca btl self,tcp -- --dim 2 \
    --particles $((weak * top)) --steps "$sw" >/dev/null
fi
if wanted output; then
  for d in 2 3; do
    n=$big2 s=$s2
    [ "$d" = 3 ] && n=$big3 s=$s3
    log="$out/output_${d}d_$top.log"
    "${launch[@]}" -np "$top" "$bin/bench_solver" --kernel wendland "${bench_args[@]}" --dim "$d" \
      --particles "$n" --steps "$s" --output 3 >"$log" 2>&1 || echo "failed: $log" >&2
    { echo "output ${d}D, $top ranks: $(grep -E '^bench_solver' "$log")"; grep -E 'time/step|snapshot|checkpoint' "$log"; } |
      tee -a "$out/output.txt" >&2
  done
fi
if command -v column >/dev/null; then column -t -s $'\t' <(cut -f1-10 "$summary"); else cut -f1-10 "$summary"; fi
