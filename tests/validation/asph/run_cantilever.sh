#!/usr/bin/env bash
# The ASPH cantilever's Table 1 (docs/asph.md): builds asph_cantilever_report and writes
# tests/validation/reports/asph_cantilever.md. About 3 minutes on one idle core.
#   tests/validation/asph/run_cantilever.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
build=${1:-$root/build}
cmake --build "$build" -j2 --target asph_cantilever_report
report=$root/tests/validation/reports/asph_cantilever.md
"$build/tests/validation/asph_cantilever_report" "$report"
echo >>"$report"
echo "Code $(git -C "$root" rev-parse --short HEAD), $(date -u +%Y-%m-%d), $(nproc) cores on this machine (shared)." >>"$report"
echo "wrote $report"
