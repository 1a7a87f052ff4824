#!/usr/bin/env bash
# Runs the Turek-Hron FSI2-type beam (make_turek_hron_fsi2.py) at several resolutions at once
# and writes each run's tip series and analysis (analyze_turek_hron_fsi2.py) to OUT.
#
#   run_turek_hron_fsi2.sh OUT WALL_SECONDS "DX:RANKS:T_END[:HOURGLASS]" ...
#
# e.g. on a 16-core machine: run_turek_hron_fsi2.sh out 470 0.05:4:80 0.0333333333:12:70
# Each run stops at T_END or after WALL_SECONDS of wall time (stop.max_wall_seconds), keeping
# its result. Needs sph-worker, orterun (or mpirun) and h5dump on PATH. The report is
# tests/validation/fsi/README.md.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=$1 wall=$2
shift 2
mkdir -p "$out"
launcher=$(command -v orterun || command -v mpirun)
pids=()
for spec in "$@"; do
  IFS=: read -r dx ranks t_end hg <<<"$spec"
  name=fsi2_dx$dx
  python3 "$here/make_turek_hron_fsi2.py" "$dx" "$t_end" "${hg:-0}" |
    sed -e "s/^output {.*/output { interval: 1000 series_interval: 0.02 }\nstop { max_wall_seconds: $wall }/" \
      >"$out/$name.textproto"
  "$launcher" --oversubscribe --bind-to none -np "$ranks" sph-worker --case "$out/$name.textproto" \
    --out "$out/$name" >"$out/$name.log" 2>&1 &
  pids+=($!)
done
for p in "${pids[@]}"; do wait "$p"; done
for spec in "$@"; do
  IFS=: read -r dx ranks t_end hg <<<"$spec"
  name=fsi2_dx$dx
  {
    echo "## dx = $dx D, $ranks ranks"
    grep -E "completed|stopped|unstable|after" "$out/$name.log" | grep -v "^step" | tail -3
    python3 "$here/analyze_turek_hron_fsi2.py" "$out/$name/result.h5" 40
  } >"$out/$name.summary" 2>&1
  # The tip series as CSV (t, x, y).
  python3 -c "
import sys; sys.path.insert(0, '$here')
from analyze_turek_hron_fsi2 import dataset
t = dataset('$out/$name/result.h5', '/series/diagnostics/time')
d = dataset('$out/$name/result.h5', '/series/elastic/beam/displacement')
print('t,x_tip,y_tip')
for k in range(min(len(t), len(d) // 2)): print(f'{t[k]:.6g},{d[2*k]:.6g},{d[2*k+1]:.6g}')
" >"$out/$name.csv"
  cat "$out/$name.summary"
done
