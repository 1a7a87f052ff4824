#!/bin/sh
# Writes the necking bar at NY particles across, runs it on RANKS MPI ranks and analyses it:
# force_NY<ny>.csv and force_NY<ny>.png here, the run in $OUT (default /tmp/necking_bar_NY<ny>).
#   usage: run_necking_bar.sh [NY=20] [RANKS=1] [V=1.0]
set -e
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
ny=${1:-20}
ranks=${2:-1}
v=${3:-1.0}
out=${OUT:-/tmp/necking_bar_NY$ny}
worker=${WORKER:-$root/build/worker/sph-worker}
python3 "$here/make_necking_bar.py" "$out.textproto" "$ny" "$v"
rm -rf "$out"
if [ "$ranks" -gt 1 ]; then
  mpirun -np "$ranks" "$worker" --case "$out.textproto" --out "$out"
else
  "$worker" --case "$out.textproto" --out "$out"
fi
/usr/bin/python3 "$here/analyze_necking_bar.py" "$out/result.h5" "$here/force_NY$ny.csv" \
  "$here/force_NY$ny.png"
