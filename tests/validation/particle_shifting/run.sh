#!/usr/bin/env bash
# Particle shifting at full size (docs/particle_shifting.md): the Taylor-Green vortex at the
# five levels of its convergence study with both speed forms, the Colagrossi dam break
# (dx = H/25, to t sqrt(g/H) = 8) with density diffusion without and with shifting, and the
# low-viscosity free drop of docs/surface_tension.md without and with shifting; then the CI
# tests (ParticleShifting.*). Writes tests/validation/reports/particle_shifting.md. About
# 15 minutes on two shared cores.
#   tests/validation/particle_shifting/run.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
build=${1:-$root/build}
tests=$build/tests/validation/sph_validation_tests
log=$(mktemp)
trap 'rm -f "$log"' EXIT
t0=$SECONDS
"$tests" --gtest_also_run_disabled_tests --gtest_filter='ParticleShifting.*' | tee "$log"
rows() { grep -E "^\| $1" "$log" || true; }
report=$root/tests/validation/reports/particle_shifting.md
{
  echo "# Particle shifting at full size"
  echo
  echo "Written by tests/validation/particle_shifting/run.sh ($(date -u +%Y-%m-%d), one rank,"
  echo "code $(git -C "$root" rev-parse --short HEAD), $((SECONDS - t0)) s on the shared 2-core"
  echo "machine). What the figures mean: docs/particle_shifting.md."
  echo
  echo "## Taylor-Green vortex (Re = 100, t = 2), shifting instead of the transport velocity"
  echo
  echo "Error: mean |u - u_exact| / (U exp(-2 nu k^2 t)) at t = 2 (the case's reference, as in"
  echo "docs/accuracy.md, where the transport-velocity scheme gives 21.14% / 14.75% / 10.26% /"
  echo "7.51% / 5.42%, order 0.98)."
  echo
  echo "| | speed | dx | error | steps | wall |"
  echo "|---|---|---:|---:|---:|---:|"
  rows "TGV"
  echo
  echo "## Colagrossi dam break, dx = H/25, wall probe against Buchner 2002 P1"
  echo
  echo "Times in t sqrt(g/H), pressures in rho g H; density diffusion Fourtakas, delta 0.1. Open:"
  echo "fluid particles with less than 95% of a kernel support (over fluid and walls, volume"
  echo "dx^2) at t = 2 / 4 / 6 / 8: the free surface, voids and splashes."
  echo
  echo "| run | first impact peak | plateau 3.2-5.2 | second impact 5.5-6.2 | noise | open | wall |"
  echo "|---|---|---|---|---|---|---|"
  rows "(Buchner|density)"
  echo
  echo "## Free drop, mu = 0.01, R/dx = 20 (docs/surface_tension.md, Not done at free surfaces)"
  echo
  echo "Laplace jump: mean pressure more than 4 h inside over t >= 1.5 against sigma / R; speeds"
  echo "are the largest fluid speed (sigma / mu = 100)."
  echo
  echo "| shifting | outcome | Laplace jump error | largest speed t <= 1 | largest speed t >= 2 |"
  echo "|---|---|---|---|---|"
  rows "(without|particle_shifting)"
  echo
  echo "## CI size (ParticleShifting.*, printed figures)"
  echo
  grep -E "^(Taylor-Green|Tank at rest|Surge front)" "$log" | sed 's/^/- /'
} >"$report"
echo "wrote $report"
