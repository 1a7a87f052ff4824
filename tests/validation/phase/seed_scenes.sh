#!/usr/bin/env bash
# Runs Fuchs 2021's three seed scenes at their coarse resolutions to their end times and
# renders frames and invariants for tests/validation/reports/seed_scenes.md:
#   tests/validation/phase/seed_scenes.sh [BUILD_DIR] [OUT_DIR]
# The 2D powder grains (dx 0.25, 157k steps) take about 40 min on one core, the 3D powder
# melting (dx 2.5 um, 104k steps) about 100 min (75 min on two ranks), its 2D slice at the
# paper's dx = 1 um (261k steps) about 19 min, the gastric boluses (dx 0.4) under 2 min.
# A finished run is kept (delete its folder to redo it). SPHD_RANKS sets the ranks (default 1).
# SPHD_PAPER=1 adds the gastric scene at the paper's dx = 0.1 (67k particles; it stops on the
# solid-fraction guard at t = 0.623 after 82 min on two ranks, see phase_change.md).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
build=${1:-$root/build}
out=${2:-$root/out/scenes}
ranks=${SPHD_RANKS:-1}
reports=$root/tests/validation/reports
mkdir -p "$out"
run() {  # name case-file [sed expression]
  local name=$1 case=$2 edit=${3:-}
  if [ -f "$out/$name/wall_seconds" ]; then echo "== $name: kept"; return; fi
  mkdir -p "$out/$name"
  sed -E "${edit:-}" "$case" >"$out/$name.textproto"
  echo "== $name ($(date +%H:%M:%S))"
  local t0=$SECONDS
  mpirun --oversubscribe --allow-run-as-root --bind-to none -np "$ranks" \
    "$build/worker/sph-worker" --case "$out/$name.textproto" --out "$out/$name" --quiet 2>&1 |
    grep -E "^(completed|unstable|error)" || true
  echo "$((SECONDS - t0))" >"$out/$name/wall_seconds"
}
run gastric_04 "$root/cases/gastric_boluses_2d.textproto" 's/^dx: 0.2$/dx: 0.4/'
run powder_2d_coarse "$root/cases/powder_grains_2d_coarse.textproto"
run powder_3d_coarse "$root/cases/powder_melting_3d_coarse.textproto"
run powder_slice_2d "$root/cases/powder_melting_slice_2d.textproto"
if [ "${SPHD_PAPER:-0}" = 1 ]; then
  run gastric_01 "$root/cases/gastric_boluses_2d.textproto" 's/^dx: 0.2$/dx: 0.1/'
fi
render=$root/tests/validation/phase/render.py
/usr/bin/python3 "$render" "$out/gastric_04/result.h5" "$reports" gastric_dx04
if [ -f "$out/gastric_01/result.h5" ]; then
  /usr/bin/python3 "$render" "$out/gastric_01/result.h5" "$reports" gastric_dx01 --frames 5
fi
/usr/bin/python3 "$render" "$out/powder_2d_coarse/result.h5" "$reports" powder_grains_2d_coarse \
  --scalar temperature --speed-max 800 --labels grain,melt,gas --frames 8
/usr/bin/python3 "$render" "$out/powder_3d_coarse/result.h5" "$reports" powder_melting_3d_coarse_xy \
  --scalar temperature --labels grain,melt,gas --frames 6 --plane xy --frames-only
/usr/bin/python3 "$render" "$out/powder_3d_coarse/result.h5" "$reports" powder_melting_3d_coarse_xz \
  --scalar temperature --labels grain,melt,gas --frames 6 --plane xz
/usr/bin/python3 "$render" "$out/powder_slice_2d/result.h5" "$reports" powder_melting_slice_2d \
  --scalar temperature --speed-max 5 --labels grain,melt,gas --frames 8
/usr/bin/python3 "$root/tests/validation/phase/scene_figures.py" "$out"
