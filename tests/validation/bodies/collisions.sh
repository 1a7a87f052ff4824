#!/usr/bin/env bash
# Validation runs of the collision models and pinned bodies too long for CI (docs/contact.md):
# the freely rotating cross of Reder et al. 2021 sec. 3.3 (cases/rotating_cross_2d.textproto,
# about 5 min on one core), then tests/validation/reports/rotating_cross.md and its plot.
#   tests/validation/bodies/collisions.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
build=${1:-$root/build}
out=${2:-$root/out/validation-collisions}
mkdir -p "$out"
if [ ! -f "$out/cross/result.h5" ] || [ ! -f "$out/cross/wall_seconds" ]; then
  t0=$SECONDS
  "$build/worker/sph-worker" --case "$root/cases/rotating_cross_2d.textproto" --out "$out/cross" --quiet
  echo "$((SECONDS - t0))" >"$out/cross/wall_seconds"
fi
/usr/bin/python3 "$root/tests/validation/bodies/cross_report.py" "$out/cross" "$root/tests/validation/reports"
