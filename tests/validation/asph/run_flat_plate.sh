#!/usr/bin/env bash
# The 3D thin flat plate of X. Tang's thesis, P-II (digest sec. 8.6, Table 2; docs/asph.md):
# writes each run's case with make_flat_plate.py, runs it with sph-worker and writes
# tests/validation/reports/asph_flat_plate.md. RUNS lists runs as
# "NZ:R:LOAD_STEPS:THRESHOLD:P_OVER_E:DAMPING" (DAMPING 0: the thesis' choice). By default the
# thesis' load at its NZ = 10, r = 8 and at NZ = 6, then a load of 1e-6 E (the linear range,
# against thin-plate theory) at NZ = 4 with r = 1, 2, 4 and 8, relaxed to 1e-9 J with a tenth
# of the damping; about 20 minutes on one core.
#   tests/validation/asph/run_flat_plate.sh [BUILD_DIR]        (RANKS=N for mpirun -np N)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../../.." && pwd)
build=${1:-$root/build}
out=${OUT:-/tmp/asph_flat_plate}
ranks=${RANKS:-1}
runs=${RUNS:-"6:8:20:0.1:0.01:0 10:8:20:0.1:0.01:0 4:1:4:1e-9:1e-6:5900 4:2:4:1e-9:1e-6:5900 4:4:4:1e-9:1e-6:5900 4:8:4:1e-9:1e-6:5900"}
mkdir -p "$out"
rows=()
for run in $runs; do
  IFS=: read -r nz r steps threshold load damping <<<"$run"
  name="nz${nz}_r${r}_${steps}_${threshold}_${load}"
  args=("$nz" "$r" "$steps" "$threshold" "$load")
  [ "$damping" != 0 ] && args+=("$damping")
  python3 "$here/make_flat_plate.py" "${args[@]}" >"$out/$name.textproto"
  rm -rf "${out:?}/$name"
  start=$SECONDS
  if [ "$ranks" -gt 1 ]; then
    mpirun -np "$ranks" "$build/worker/sph-worker" --case "$out/$name.textproto" --out "$out/$name" \
      >"$out/$name.log" 2>&1
  else
    "$build/worker/sph-worker" --case "$out/$name.textproto" --out "$out/$name" >"$out/$name.log" 2>&1
  fi
  wall=$((SECONDS - start))
  rows+=("$nz $r $steps $threshold $load $wall $out/$name/result.h5")
done
python3 "$here/flat_plate_report.py" "$root/tests/validation/reports/asph_flat_plate.md" \
  "$(git -C "$root" rev-parse --short HEAD)" "$ranks" "${rows[@]}"
