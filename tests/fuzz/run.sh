#!/usr/bin/env bash
# Builds the fuzz targets with clang (libFuzzer, AddressSanitizer, UBSan) and runs each for a
# bounded time from its seed corpus and saved findings (tests/fuzz/README.md).
#   tests/fuzz/run.sh [SECONDS_PER_TARGET] [BUILD_DIR]      (defaults: 60, build-fuzz)
# CI runs it with the default; run it for hours by hand before a release. A finding is saved
# as BUILD_DIR/findings/<target>/crash-* (or leak-, timeout-, oom-); the script then exits 1.
# A finding, once fixed, goes to tests/fuzz/regressions/<target>/ with a name that says what
# it was, and ctest replays it on every build from then on.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
seconds=${1:-60}
build=${2:-$root/build-fuzz}
mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSPHD_FUZZ=ON >"$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j"$(nproc)" --target case_text_fuzzer rpc_fuzzer
export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
export LSAN_OPTIONS=suppressions=$root/tests/fuzz/lsan.supp
export UBSAN_OPTIONS=print_stacktrace=1
# One target per process, both at once: each gets its SECONDS on its own core where there are
# two (CI's machine), so the suite waits SECONDS, not twice that.
fuzz_target() {
  local target=$1 corpus=$build/corpus/$1 findings=$build/findings/$1
  mkdir -p "$corpus" "$findings"
  local seeds=() dirs=("$root/tests/fuzz/corpus/$target" "$root/tests/fuzz/regressions/$target")
  # Every shipped case is a seed of the case-text target.
  [ "$target" = case_text ] && dirs+=("$root/cases" "$root/tests/service/cases")
  for d in "${dirs[@]}"; do [ -d "$d" ] && seeds+=("$d"); done
  "$build/tests/fuzz/${target}_fuzzer" -max_total_time="$seconds" -timeout=30 \
    -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1 -artifact_prefix="$findings/" \
    "$corpus" "${seeds[@]}" >"$build/$target.log" 2>&1
}
targets=(case_text rpc)
pids=()
for target in "${targets[@]}"; do
  echo "fuzzing $target for $seconds s"
  fuzz_target "$target" &
  pids+=($!)
done
passed=0
failed=0
for k in "${!targets[@]}"; do
  target=${targets[$k]}
  if wait "${pids[$k]}"; then
    passed=$((passed + 1))
    echo "$target:"
    grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|#[0-9]+ +DONE)" \
      "$build/$target.log" || true
  else
    failed=$((failed + 1))
    tail -60 "$build/$target.log"
    echo "fuzz finding in $target: $(ls "$build/findings/$target")"
  fi
done
echo "fuzz: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
