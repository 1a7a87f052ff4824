#!/bin/sh
# The mode-2 oscillating drop at R/dx = 20
# (SurfaceTension.DISABLED_OscillatingDropMode2PeriodFine, about 60 s on one core, eight times
# the ctest size): prints the period against Lamb's and against the viscous normal mode
# (viscous_drop_mode.h), and the decay rate, quoted in docs/surface_tension.md.
# usage: tests/validation/surface_tension/oscillating_drop_fine.sh BUILD_DIR
set -eu
build=${1:?usage: $0 BUILD_DIR}
exec "$build/tests/validation/sph_validation_tests" \
  --gtest_filter='SurfaceTension.DISABLED_OscillatingDropMode2PeriodFine' \
  --gtest_also_run_disabled_tests
