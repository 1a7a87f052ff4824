#!/usr/bin/env bash
# Density diffusion at full size (docs/density_diffusion.md): the Colagrossi dam break
# (cases/colagrossi_dambreak_2d, dx = H/50, to t sqrt(g/H) = 8) without density diffusion and
# with both forms, its wall probe against Buchner 2002 P1, and the Martin-Moyce column
# (dx = a/50) without and with it, its surge front against Koshizuka & Oka 1996. Writes
# tests/validation/reports/density_diffusion.md. About 15 minutes a dam-break run on two
# idle cores.
#   tests/validation/density_diffusion/run.sh [BUILD_DIR] [OUT_DIR]
# SPHD_RANKS sets the ranks (default 2); a finished run is kept (delete its folder to redo it).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
build=${1:-$root/build}
out=${2:-$root/out/validation-density-diffusion}
ranks=${SPHD_RANKS:-2}
mkdir -p "$out"
plain='s/^fluid_model \{ density: CONTINUITY artificial_viscosity: 0.1 \}$/&/'
fourtakas='s/^fluid_model \{ density: CONTINUITY artificial_viscosity: 0.1 \}$/fluid_model { density: CONTINUITY artificial_viscosity: 0.1 density_diffusion { form: FOURTAKAS delta: 0.1 } }/'
molteni='s/^fluid_model \{ density: CONTINUITY artificial_viscosity: 0.1 \}$/fluid_model { density: CONTINUITY artificial_viscosity: 0.1 density_diffusion { form: MOLTENI_COLAGROSSI delta: 0.1 } }/'
run() {  # name case-file sed-expression
  local name=$1 case=$2 edit=$3
  if [ -f "$out/$name/wall_seconds" ]; then echo "== $name: kept from an earlier run"; return; fi
  mkdir -p "$out/$name"
  local file=$out/$name.textproto
  local abs="s#file: \"([^/\"][^\"]*)\"#file: \"$(dirname "$case")/\\1\"#"
  sed -E "$abs;$edit" "$case" >"$file"
  if [ "$edit" != "$plain" ] && ! grep -q density_diffusion "$file"; then
    echo "$name: the edit did not apply to $case" >&2
    exit 1
  fi
  echo "== $name ($(date +%H:%M:%S))"
  local t0=$SECONDS
  mpirun --oversubscribe --allow-run-as-root --bind-to none -np "$ranks" \
    "$build/worker/sph-worker" --case "$file" --out "$out/$name" --quiet 2>&1 |
    grep -E "^(completed|unstable|error)" || true
  echo "$((SECONDS - t0))" >"$out/$name/wall_seconds"
}
colagrossi=$root/cases/colagrossi_dambreak_2d.textproto
column=$root/cases/dambreak_martin_moyce_2d.textproto
run colagrossi_plain "$colagrossi" "$plain"
run colagrossi_fourtakas "$colagrossi" "$fourtakas"
run colagrossi_molteni "$colagrossi" "$molteni"
run front_plain "$column" "$plain"
run front_fourtakas "$column" "$fourtakas"
report=$root/tests/validation/reports/density_diffusion.md
{
  echo "# Density diffusion at full size"
  echo
  echo "Written by tests/validation/density_diffusion/run.sh ($(date -u +%Y-%m-%d), $ranks ranks,"
  echo "code $(git -C "$root" rev-parse --short HEAD)). Figures by"
  echo "tests/validation/impact_pressure.h; what they mean: docs/density_diffusion.md."
  echo
  echo "## Colagrossi dam break, dx = H/50, wall probe at y = 0.2 H against Buchner 2002 P1"
  echo
  echo "Times in t sqrt(g/H), pressures in rho g H."
  echo
  "$build/tests/validation/impact_report" probe \
    "without" "$out/colagrossi_plain" \
    "Fourtakas, delta 0.1" "$out/colagrossi_fourtakas" \
    "Molteni-Colagrossi, delta 0.1" "$out/colagrossi_molteni"
  echo
  echo "## Martin-Moyce column, dx = a/50, surge front against Koshizuka & Oka 1996"
  echo
  "$build/tests/validation/impact_report" front \
    "without" "$out/front_plain" \
    "Fourtakas, delta 0.1" "$out/front_fourtakas"
  echo
  echo "Wall seconds per run ($ranks ranks):"
  for r in colagrossi_plain colagrossi_fourtakas colagrossi_molteni front_plain front_fourtakas; do
    echo "- $r: $(cat "$out/$r/wall_seconds") s"
  done
} >"$report"
echo "wrote $report"
