#!/usr/bin/env bash
# The stability suite outside ctest, writing docs/stability.md with the figures over time.
#   tests/stability/run.sh [--full] [BUILD_DIR]
# Without --full the hard cases run at the reduced (CI) size, in a few minutes on two cores;
# --full runs the case files as shipped (SPHD_STABILITY_FULL=1: finer dx, the long end
# times the cases state; about 1.5 h on one core) and writes docs/stability-full.md. The
# guard-trip tests run either way.
set -euo pipefail
full=0
if [ "${1:-}" = "--full" ]; then full=1; shift; fi
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${1:-$root/build}
out=$root/out/stability
mkdir -p "$out"
log=$out/$([ $full = 1 ] && echo full || echo reduced).log
export SPHD_STABILITY_FULL=$full
t0=$SECONDS
echo "code version: $(git -C "$root" describe --always --dirty)" >"$log"
# A failing case is reported on the page, not fatal to the others.
"$build/tests/stability/sph_stability_tests" --gtest_color=no 2>&1 | tee -a "$log" || true
echo "suite wall time: $((SECONDS - t0)) s" >>"$log"
# The reduced and the full run each have their page.
page=$root/docs/stability$([ $full = 1 ] && echo -full || true).md
/usr/bin/python3 "$root/tests/stability/report.py" "$log" "$build/test-output" \
  "$page" "$root/docs/stability" $([ $full = 1 ] && echo full || echo reduced)
