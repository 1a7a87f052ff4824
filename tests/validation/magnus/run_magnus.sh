#!/usr/bin/env bash
# Magnus effect benchmark (Reder et al. 2021 sec. 3.2, Table 3; Mittal & Kumar 2003): runs
# cases/magnus_cylinder_2d.textproto at gamma = omega D / (2 U) = 0, 1, 2, 3, then writes
# tests/validation/reports/magnus.md and its plot (magnus_report.py).
#   tests/validation/magnus/run_magnus.sh [BUILD_DIR] [OUT_DIR]
# SPHD_MAGNUS_RES="10 20" picks the resolutions D/dx (default 10; 20 takes about 8 times as
# long), SPHD_MAGNUS_GAMMAS="0 1" the rates (default 0 1 2 3), SPHD_MAGNUS_END the end time
# (default 40 D/U; other end times name the runs g<gamma>_r<D/dx>_t<end>: the report's
# resolution table compares the lift of all gamma = 1 runs over 5 <= t <= 10). Each run is
# one rank (`nice -n 5`); a finished run is kept (delete its folder to redo it). The sound
# speed grows with gamma (10, 10, 15, 20) so that the Mach number near the spinning wall stays
# about 0.2; gamma = 0 is spun for t in [2, 3] at omega = 1 to break the symmetry of the
# lattice so that shedding starts early. The fluid's pressure level (EOS background pressure =
# outlet pressure) is 0.1 rho0 c^2 (10, 10, 22.5, 40). Then a sweep of that level at D/dx = 5
# (about 4 minutes), the fluid next to the turning wall at levels 0 and 10 (D/dx = 10, about
# 4 minutes) and the torque checks (about 2 minutes).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
build=${1:-$root/build}
out=${2:-$root/out/validation-magnus}
mkdir -p "$out"
end=${SPHD_MAGNUS_END:-40}
# run_case NAME D/dx GAMMA END_TIME [PRESSURE_LEVEL]: writes OUT/NAME.textproto from the case
# and runs it into OUT/NAME (kept when OUT/NAME/wall_seconds exists). The pressure level
# (EOS background pressure = outlet pressure) defaults to 0.1 rho0 c^2.
run_case() {
  local name=$1 res=$2 g=$3 t_end=$4 c chi omega dx wide
  local snapshots=${SNAPSHOT_INTERVAL:-10}
  if [ -f "$out/$name/wall_seconds" ]; then echo "== $name: kept from an earlier run"; return; fi
  case $g in 0 | 1) c=10 ;; 2) c=15 ;; *) c=20 ;; esac
  chi=${5:-$(/usr/bin/python3 -c "print($c * $c / 10)")}
  if [ "$g" = 0 ]; then
    omega="angular_velocity { constant: 1 start_time: 2 end_time: 3 }"
  else
    omega="angular_velocity { constant: -$((2 * g)) }"
  fi
  dx=$(/usr/bin/python3 -c "print(1 / $res)")
  # Walls and buffers are 0.4 thick, at least the kernel support 3 dx from D/dx = 7.5 up;
  # coarser runs get 0.6.
  wide=""
  if [ "$res" -lt 8 ]; then wide="s/-4\.4/-4.6/g; s/10\.4/10.6/g; s/y: 4\.4/y: 4.6/g;"; fi
  mkdir -p "$out/$name"
  sed -E "$wide s/^dx: 0\.1$/dx: $dx/; s/sound_speed: 10 background_pressure: 10 \}  # MAGNUS_SOUND_SPEED/sound_speed: $c background_pressure: $chi }/;
          s/pressure: 10  # MAGNUS_OUTLET_PRESSURE/pressure: $chi/;
          s/angular_velocity \{ constant: -2 \}  # MAGNUS_OMEGA/$omega/;
          s/end_time: 40 \}  # MAGNUS_END_TIME/end_time: $t_end }/;
          s/output \{ interval: 10 /output { interval: $snapshots /" \
    "$root/cases/magnus_cylinder_2d.textproto" >"$out/$name.textproto"
  for k in MAGNUS_SOUND_SPEED MAGNUS_OUTLET_PRESSURE MAGNUS_OMEGA MAGNUS_END_TIME; do
    if grep -q "$k" "$out/$name.textproto"; then echo "$k not replaced" >&2; exit 1; fi
  done
  echo "== $name: gamma $g, D/dx $res, c $c, pressure level $chi ($(date +%H:%M:%S))"
  local t0=$SECONDS
  nice -n 5 "$build/worker/sph-worker" --case "$out/$name.textproto" --out "$out/$name" --quiet 2>&1 |
    grep -E "^(completed|unstable|error)" | tee "$out/$name/outcome" || true
  # The report marks a run that stopped early.
  if grep -q "^unstable" "$out/$name/outcome"; then mv "$out/$name/outcome" "$out/$name/unstable"; fi
  echo "$((SECONDS - t0))" >"$out/$name/wall_seconds"
}
for res in ${SPHD_MAGNUS_RES:-10}; do
  for g in ${SPHD_MAGNUS_GAMMAS:-0 1 2 3}; do
    name=g${g}_r${res}
    if [ "$end" != 40 ]; then name=${name}_t$end; fi
    run_case "$name" "$res" "$g" "$end"
  done
done
# The pressure level: D/dx = 5, the lift at gamma = 1 over 5 <= t <= 10 and the drag at
# gamma = 0 over 10 <= t <= 20 for levels from 0 to 30 rho U^2 (about 15 s each), the lift runs
# with a snapshot every D/U for the lowest pressure.
for chi in 0 1 2 4 6 10 30; do
  SNAPSHOT_INTERVAL=1 run_case level_g1_p$chi 5 1 10 "$chi"
  run_case level_g0_p$chi 5 0 20 "$chi"
done
# The fluid next to the turning wall at a zero level and at chi = 10: D/dx = 10, gamma = 1 to
# t = 15, a snapshot every D/U (about 100 s each).
for chi in 0 10; do
  SNAPSHOT_INTERVAL=1 run_case wall_g1_p$chi 10 1 15 "$chi"
done
# The torque check: circular Couette flow about a turning cylinder, R1/dx = 10 and 20 (5 s and
# 35 s).
for r in 10 20; do
  if [ ! -f "$out/couette_r$r/result.h5" ]; then
    sed "s/^dx: 0.05$/dx: $(/usr/bin/python3 -c "print(0.5 / $r)")/" \
      "$root/tests/validation/magnus/rotating_couette_2d.textproto" >"$out/couette_r$r.textproto"
    nice -n 5 "$build/worker/sph-worker" --case "$out/couette_r$r.textproto" --out "$out/couette_r$r" \
      --quiet 2>&1 | grep -E "^(completed|unstable|error)" || true
  fi
done
# The same in rigid rotation: ring turned with the cylinder, fluid started turning with them.
# Every torque should vanish (3 s).
if [ ! -f "$out/couette_rigid/result.h5" ]; then
  sed 's/motion_type: FIXED/motion_type: PRESCRIBED\n  motion { angular_velocity { constant: -2 } }/;
       s/shape { ball { radius: 1 } } }/shape { ball { radius: 1 } } initial_velocity_field { linear { gradient_x { y: 2 } gradient_y { x: -2 } } } }/;
       s/end_time: 8/end_time: 3/; s/interval: 8/interval: 3/' \
    "$root/tests/validation/magnus/rotating_couette_2d.textproto" >"$out/couette_rigid.textproto"
  nice -n 5 "$build/worker/sph-worker" --case "$out/couette_rigid.textproto" --out "$out/couette_rigid" \
    --quiet 2>&1 | grep -E "^(completed|unstable|error)" || true
fi
# A free body spun by its fluid: the ring turned, the cylinder pinned and free to turn, the
# fluid at rest at t = 0; the cylinder should end turning with the ring (12 s).
if [ ! -f "$out/couette_pinned/result.h5" ]; then
  /usr/bin/python3 - "$root/tests/validation/magnus/rotating_couette_2d.textproto" \
    "$out/couette_pinned.textproto" <<'PY'
import sys
s = open(sys.argv[1]).read()
turned = "  motion { angular_velocity { constant: -2 } }\n"
s = s.replace("motion_type: PRESCRIBED\n  shape { ball { radius: 0.5 } }\n" + turned,
              "motion_type: PINNED\n  shape { ball { radius: 0.5 } }\n")
s = s.replace("motion_type: FIXED\n  shape { shell { inner { ball { radius: 1 } } } }\n",
              "motion_type: PRESCRIBED\n  shape { shell { inner { ball { radius: 1 } } } }\n" + turned)
s = s.replace("end_time: 8", "end_time: 12").replace("interval: 8", "interval: 12")
assert "PINNED" in s and s.count("angular_velocity") == 1, "rotating_couette_2d changed"
open(sys.argv[2], "w").write(s)
PY
  nice -n 5 "$build/worker/sph-worker" --case "$out/couette_pinned.textproto" --out "$out/couette_pinned" \
    --quiet 2>&1 | grep -E "^(completed|unstable|error)" || true
fi
# The 3D check: a turning sphere inside a fixed spherical shell (about 30 s).
if [ ! -f "$out/spheres_3d/result.h5" ]; then
  nice -n 5 "$build/worker/sph-worker" --case "$root/tests/validation/magnus/rotating_spheres_3d.textproto" \
    --out "$out/spheres_3d" --quiet 2>&1 | grep -E "^(completed|unstable|error)" || true
fi
/usr/bin/python3 "$root/tests/validation/magnus/magnus_report.py" "$out" "$root/tests/validation/reports"
