#!/usr/bin/env bash
# The service on one machine in one command: starts sph-server and a 2-rank worker pool on
# loopback, submits a dam break, watches it, fetches and verifies the result, then stops
# everything cleanly.
#
#   deploy/quickstart.sh [CASE.textproto]        (default: cases/dambreak_2d.textproto)
#
# Environment: SPHD_BUILD (build directory, default ./build; built here when the programs are
# missing), SPHD_DEMO_DIR (work directory, default a new /tmp/sphd-demo-*), SPHD_RANKS (2).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SPHD_BUILD:-$root/build}
case_file=${1:-$root/cases/dambreak_2d.textproto}
ranks=${SPHD_RANKS:-2}
work=${SPHD_DEMO_DIR:-$(mktemp -d /tmp/sphd-demo-XXXXXX)}
mkdir -p "$work"

server_bin=$build/server/sph-server
worker_bin=$build/worker/sph-worker
sphctl=$build/client/sphctl
if [ ! -x "$server_bin" ] || [ ! -x "$worker_bin" ] || [ ! -x "$sphctl" ]; then
  echo "== building sph-server, sph-worker and sphctl in $build"
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build "$build" -j"$(nproc)" --target sph-server sph-worker sphctl
fi

server_pid=""
pool_pid=""
cleanup() {
  # The pool first (SIGUSR1: checkpoint a running job and hand it back), then the server.
  if [ -n "$pool_pid" ] && kill -0 "$pool_pid" 2>/dev/null; then
    kill -USR1 "$pool_pid" 2>/dev/null || true
    wait "$pool_pid" 2>/dev/null || true
  fi
  if [ -n "$server_pid" ] && kill -0 "$server_pid" 2>/dev/null; then
    kill -TERM "$server_pid"
    wait "$server_pid" 2>/dev/null || true
  fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

echo "== starting sph-server (logs in $work/server.log)"
"$server_bin" --address 127.0.0.1:0 --address-file "$work/address" --db "$work/sphd.db" \
  --results "$work/results" >"$work/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 100); do [ -s "$work/address" ] && break; sleep 0.1; done
[ -s "$work/address" ] || { cat "$work/server.log"; echo "sph-server did not start" >&2; exit 1; }
export SPHCTL_SERVER=$(cat "$work/address")
"$sphctl" health

echo "== starting a worker pool of $ranks ranks (logs in $work/pool.log)"
mpi_args=(--oversubscribe --bind-to none --mca btl_vader_single_copy_mechanism none)
if [ "$(id -u)" = 0 ]; then mpi_args+=(--allow-run-as-root); fi
mpirun "${mpi_args[@]}" -np "$ranks" "$worker_bin" --server "$SPHCTL_SERVER" --idle-exit 600 \
  --checkpoint-interval 30 >"$work/pool.log" 2>&1 &
pool_pid=$!

echo "== $case_file"
"$sphctl" submit "$case_file" --dry-run
job=$("$sphctl" submit "$case_file" --json | sed -n 's/.*"id":"\([^"]*\)".*/\1/p')
echo "== submitted $job; watching (Ctrl-C stops the demo)"
"$sphctl" watch "$job"

echo "== fetching the result"
"$sphctl" fetch "$job" -o "$work/$job"
"$sphctl" status "$job"
echo
echo "Result: $work/$job/result.h5 (open $work/$job/result.xmf in ParaView)"
