#!/bin/bash
# Runs the four configurations of the reduced TFSI heated channel (make_cases.py) with
# sph-worker, two at a time at low priority, then writes the report (analyze.py).
# usage: run.sh WORKER OUT_DIR [DX] [T_END]
set -euo pipefail
worker=$1 out=$2 dx=${3:-0.05} t_end=${4:-20}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
python3 "$here/make_cases.py" "$out/cases" "$dx" "$t_end"
run() { nice -n 19 "$worker" --case "$out/cases/tfsi_channel_$1.textproto" --out "$out/$1" \
          > "$out/$1.log" 2>&1 || echo "configuration $1 failed: see $out/$1.log"; }
run I & run II & wait
run III & run IV & wait
python3 "$here/analyze.py" "$out" > "$out/report.md"
cat "$out/report.md"
