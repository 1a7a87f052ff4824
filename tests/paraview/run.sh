#!/usr/bin/env bash
# ParaView 5.11 draws sph-worker's results as particles with every reader (ctest label
# paraview): runs two small cases, one on two ranks with a fixed particle count (the tiny dam
# break: one connectivity dataset, written by both ranks, shared by every snapshot) and one
# with an outflow (a body leaving a channel to t = 0.3: the count changes between snapshots),
# and checks each with check_result_xmf.py in pvpython under
# xvfb-run. Needs Debian's paraview, python3-paraview and xvfb (deploy/install-deps.sh
# --with-paraview).
#   tests/paraview/run.sh SPH_WORKER WORK_DIR MPIRUN...
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
worker=$1 work=$2
shift 2
rm -rf "$work"
mkdir -p "$work"
sed 's/end_time: 0.6/end_time: 0.3/' "$root/cases/channel_body_outflow_2d.textproto" \
  >"$work/channel_body_outflow_2d.textproto"
for run in "2 $root/tests/service/cases/tiny_dam_break_2d" "1 $work/channel_body_outflow_2d"; do
  read -r ranks c <<<"$run"
  name=$(basename "$c")
  "$@" -np "$ranks" "$worker" --case "$c.textproto" --out "$work/$name" --quiet
done
# One X server for both checks, at a display number picked at random: back-to-back xvfb-run
# calls that both started at :99 raced, the second pvpython meeting the first's dying server
# ("bad X server connection", SIGABRT) in one run of four.
xvfb-run -a -n $((100 + RANDOM % 800)) -s "-screen 0 1024x768x24" \
  pvpython "$here/check_result_xmf.py" "$work/tiny_dam_break_2d" "$work/channel_body_outflow_2d"
