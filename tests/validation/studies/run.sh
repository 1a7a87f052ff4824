#!/usr/bin/env bash
# Runs the shipped convergence studies (docs/accuracy.md) with sph-worker in local mode on one
# rank, then writes docs/accuracy.md and the plots in docs/accuracy/ from their results.
#
#   tests/validation/studies/run.sh                 # every study, full ladders (half an hour
#                                                   # on two shared cores)
#   tests/validation/studies/run.sh --coarse        # the three coarsest levels of each (minutes)
#   tests/validation/studies/run.sh --only poiseuille,couette
#
# Each study is one command (printed before it runs). Results go to $STUDY_OUT (default
# build/studies/<name>/); running again reuses the levels that are over, so an interrupted run
# continues where it stopped and the report can be regenerated without running anything
# (--report-only). --coarse writes to <name>-coarse/ and does not touch docs/. A study with no
# results under $STUDY_OUT (--only ran others) keeps its section and summary row as
# docs/accuracy.md has them.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
build=${BUILD_DIR:-$root/build}
out=${STUDY_OUT:-$build/studies}
worker=$build/worker/sph-worker
python=${SPHD_PYTHON:-/usr/bin/python3}

# name | case | ladder (sph-worker flags). Coarsest level first; cheap studies first.
studies=(
  "conduction|cases/conduction_slab_2d.textproto|--study-refine 7"
  "poiseuille|cases/studies/poiseuille_2d.textproto|--study-refine 7"
  "couette|cases/studies/couette_2d.textproto|--study-refine 7"
  "taylor_green|cases/taylor_green_2d.textproto|--study-dx 0.05,0.0354,0.025,0.0177,0.0125"
  "hydrostatic|cases/hydrostatic_tank_2d.textproto|--study-dx 0.05,0.0333,0.025,0.0167"
  "hydrostatic_steady|cases/studies/hydrostatic_tank_2d.textproto|--study-dx 0.05,0.0333,0.025,0.0167"
  "cooled_block|cases/cooled_block_channel_2d.textproto|--study-refine 4"
  "dam_break|cases/dambreak_martin_moyce_2d.textproto|--study-dx 0.05,0.0354,0.025,0.0177"
  "falling_disk|cases/studies/falling_disk_2d.textproto|--study-refine 4"
  "oscillating_plate|cases/studies/oscillating_plate_2d.textproto|--study-dx 0.004,0.002,0.001,0.0005"
)

coarse=0
report_only=0
only=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --coarse) coarse=1 ;;
    --report-only) report_only=1 ;;
    --only) only=$2; shift ;;
    *) echo "usage: $0 [--coarse] [--only NAME,NAME] [--report-only]" >&2; exit 2 ;;
  esac
  shift
done

if [[ ! -x $worker ]]; then
  echo "no $worker: build first (cmake -S . -B build && cmake --build build -j2)" >&2
  exit 1
fi

# The three coarsest levels of a ladder.
coarsen() {
  local flags=$1
  if [[ $flags == --study-refine* ]]; then
    echo "--study-refine 3"
  else
    local list=${flags#--study-dx }
    echo "--study-dx $(echo "$list" | cut -d, -f1-3)"
  fi
}

names=()
for entry in "${studies[@]}"; do
  IFS='|' read -r name case flags <<<"$entry"
  if [[ -n $only && ",$only," != *",$name,"* ]]; then continue; fi
  dir=$out/$name
  if [[ $coarse == 1 ]]; then
    flags=$(coarsen "$flags")
    dir=$out/$name-coarse
  fi
  names+=("$name")
  [[ $report_only == 1 ]] && continue
  mkdir -p "$dir"
  echo "== $name: sph-worker --case $case --out $dir $flags"
  start=$(date +%s)
  # shellcheck disable=SC2086
  if ! "$worker" --case "$root/$case" --out "$dir" $flags --quiet 2>&1 | tee "$dir.log"; then
    echo "   $name: the study did not complete (see $dir.log)"
  fi
  git -C "$root" describe --always --dirty >"$dir/code_version"
  echo "   $name took $(( $(date +%s) - start )) s"
done

if [[ $coarse == 1 ]]; then
  echo "coarse run: results in $out/*-coarse/ (docs/ unchanged)"
  exit 0
fi
printf '%s\n' "${studies[@]}" |
  "$python" "$root/tests/validation/studies/report.py" --results "$out" --docs "$root/docs"
echo "wrote $root/docs/accuracy.md"
