#!/bin/sh
# Runs the thesis' porous beam (cases/porous_beam_2d.textproto; digest sec. 8.13) and writes its
# report here: porous_beam.csv (the centre's deflection and the inner steps at each load step) and
# porous_beam.md. The run goes to $OUT (default /tmp/porous_beam).
#   usage: run_porous_beam.sh [RANKS=1]
set -e
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
ranks=${1:-1}
out=${OUT:-/tmp/porous_beam}
worker=${WORKER:-$root/build/worker/sph-worker}
rm -rf "$out"
start=$(date +%s)
if [ "$ranks" -gt 1 ]; then
  mpirun -np "$ranks" "$worker" --case "$root/cases/porous_beam_2d.textproto" --out "$out"
else
  "$worker" --case "$root/cases/porous_beam_2d.textproto" --out "$out"
fi
wall=$(( $(date +%s) - start ))
python3 "$here/analyze_porous_beam.py" "$out/result.h5" "$here/porous_beam.csv" \
  "$here/porous_beam.md" "$wall" "$ranks"
