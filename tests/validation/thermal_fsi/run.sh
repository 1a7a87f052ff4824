#!/bin/bash
# Runs the four configurations of the reduced TFSI heated channel (make_cases.py) with
# sph-worker, two at a time at low priority, then writes the report (analyze.py).
# usage: run.sh WORKER OUT_DIR [DX] [T_END] [T_FROM]
# With RANKS=n in the environment the four run at once, each on n MPI ranks (orterun or
# mpirun from PATH; a 16-core machine: RANKS=4), and with WALL=s each stops after s seconds of
# wall time (stop.max_wall_seconds), keeping its result. T_FROM: Nu is averaged over t >= T_FROM
# (default: the second half of the run).
set -euo pipefail
worker=$1 out=$2 dx=${3:-0.05} t_end=${4:-20} t_from=${5:-}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
python3 "$here/make_cases.py" "$out/cases" "$dx" "$t_end"
if [ -n "${WALL:-}" ]; then
  for f in "$out"/cases/*.textproto; do echo "stop { max_wall_seconds: $WALL }" >>"$f"; done
fi
run() {
  local launch=(nice -n 19)
  if [ -n "${RANKS:-}" ]; then
    launch=("$(command -v orterun || command -v mpirun)" --oversubscribe --bind-to none -np "$RANKS")
  fi
  "${launch[@]}" "$worker" --case "$out/cases/tfsi_channel_$1.textproto" --out "$out/$1" \
    >"$out/$1.log" 2>&1 || echo "configuration $1 failed: see $out/$1.log"
}
if [ -n "${RANKS:-}" ]; then
  run I & run II & run III & run IV & wait
else
  run I & run II & wait
  run III & run IV & wait
fi
python3 "$here/analyze.py" "$out" $t_from >"$out/report.md"
cat "$out/report.md"
