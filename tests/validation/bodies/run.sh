#!/usr/bin/env bash
# Rigid-body validation runs too long for CI (issue: mobile rigid bodies and contact). Runs
# the cases with sph-worker, then writes tests/validation/reports/bodies.md and its plots.
#   tests/validation/bodies/run.sh [--full] [BUILD_DIR] [OUT_DIR]
# Default: falling disk at D/dx = 12.5, shear migration at D/dx = 6.25, settling sphere at
# D/dx = 6, the 27-sphere box. --full adds the falling disk at D/dx = 25 and the migration
# at D/dx = 12.5 (hours on two cores). SPHD_BODY_RUNS="name ..." runs only those (the report
# still covers every run found in OUT_DIR); SPHD_RANKS sets the ranks (default 2).
set -euo pipefail
full=0
if [ "${1:-}" = "--full" ]; then full=1; shift; fi
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
build=${1:-$root/build}
out=${2:-$root/out/validation-bodies}
ranks=${SPHD_RANKS:-2}
mkdir -p "$out"
run() {  # name case-file [sed expression]; a finished run is kept (delete its folder to redo it)
  local name=$1 case=$2 edit=${3:-}
  if [ -n "${SPHD_BODY_RUNS:-}" ] && [[ " $SPHD_BODY_RUNS " != *" $name "* ]]; then return; fi
  if [ -f "$out/$name/wall_seconds" ]; then echo "== $name: kept from an earlier run"; return; fi
  mkdir -p "$out/$name"
  local file=$out/$name.textproto
  # The copy lives elsewhere: relative data files (reference curves) keep pointing at theirs.
  local abs="s#file: \"([^/\"][^\"]*)\"#file: \"$(dirname "$case")/\\1\"#"
  sed -E "$abs${edit:+;$edit}" "$case" >"$file"
  echo "== $name ($(date +%H:%M:%S))"
  local t0=$SECONDS
  # A run that ends unstable is reported, not fatal to the others.
  mpirun --oversubscribe --allow-run-as-root --bind-to none -np "$ranks" \
    "$build/worker/sph-worker" --case "$file" --out "$out/$name" --quiet 2>&1 | grep -E "^(completed|unstable|error)" || true
  echo "$((SECONDS - t0))" >"$out/$name/wall_seconds"
}
run falling_disk_12 "$root/cases/falling_disk_2d.textproto" 's/end_time: 0.8/end_time: 1.0/'
run migration_6 "$root/cases/disk_shear_migration_2d.textproto" 's/^dx: 0.0002/dx: 0.0004/'
run settling_sphere_6 "$root/cases/settling_sphere_3d.textproto"
run spheres_box "$root/cases/spheres_box_3d.textproto"
if [ $full = 1 ]; then
  run falling_disk_25 "$root/cases/falling_disk_2d.textproto" 's/^dx: 0.0002/dx: 0.0001/; s/end_time: 0.8/end_time: 1.0/'
  run migration_12 "$root/cases/disk_shear_migration_2d.textproto"
fi
/usr/bin/python3 "$root/tests/validation/bodies/report.py" "$out" "$root/tests/validation/reports"
