#!/usr/bin/env bash
# Issue 21, step 1: the per-frame ground plane lsm-build ranges with against the simulator's true
# plane, on the curved wide world of bench_vp_calibration.sh (samples/demo/crowd-frames.json
# --world-curve-amplitude 60 --world-max-lanes-per-direction 3, N traversals at --level frames).
# bench_attitude_error splits the lateral error of ranged lane points into normal (pitch / roll)
# and camera height, and the normal error into what the tilt window leaves of the true suspension
# motion and what the dead-reckoned gyro adds. Rows: the former default (2 s box window, height
# fixed) and the current one (4 s Hann window, height following the tilt), plus the single
# changes. Deterministic (no timing): counts and RMS only. Writes docs/performance-attitude.md.
# usage: scripts/bench/bench_attitude_error.sh [BIN_DIR=build/bin] [WORK=/tmp/attitude-error]
# env: TRAVERSALS=3
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
work=${2:-/tmp/attitude-error}
n=${TRAVERSALS:-3}
rm -rf "$work/sim"
mkdir -p "$work"
"$bin/simulate" -q --config "$root/samples/demo/crowd-frames.json" --world-curve-amplitude 60 \
  --world-max-lanes-per-direction 3 --traversals "$n" --level frames --frames-masks 0 \
  -o "$work/sim" > /dev/null
drives=()
for d in "$work"/sim/frames/*/; do drives+=(--drive "$d"); done
doc="$root/docs/performance-attitude.md"
{
  echo "# Performance: per-frame ground plane against the simulator's truth (issue 21)"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%MZ) (no timings: RMS of deterministic runs)"
  echo "- command: \`TRAVERSALS=$n scripts/bench/bench_attitude_error.sh BIN_DIR WORK\`: \`simulate"
  echo "  --config samples/demo/crowd-frames.json --world-curve-amplitude 60"
  echo "  --world-max-lanes-per-direction 3 --traversals $n --level frames\`, then"
  echo "  \`bench_attitude_error --drive ...\` (lsm-build's calibrateGroundPlanes on the dead-reckoned"
  echo "  ego-motion, VP on, against truth/poses.csv: level road, true body attitude per frame)."
  echo "- lateral RMS [m] of lane points per band of lateral offset from the car: the same pixel"
  echo "  ranged (eq. 1) on the plane used and on the true plane, so pixel noise is left out."
  echo
  echo "## Former default: tilt_window 2 s, box, camera height fixed"
  echo
  "$bin/bench_attitude_error" "${drives[@]}" --tilt-window 2 --tilt-weighting box \
    --tilt-moves-height 0
  echo
  echo "## Current default: tilt_window 4 s, Hann, camera height following the tilt"
  echo
  "$bin/bench_attitude_error" "${drives[@]}"
  echo
  echo "## One change at a time (first table row only)"
  echo
  echo "| plane used for ranging | lateral RMS 0-3 m | 3-6 m | 6-9 m | 9-12 m |"
  echo "|---|---|---|---|---|"
  for cfg in "2 box 1" "4 box 0" "4 box 1" "4 hann 0" "3 hann 1" "6 hann 1"; do
    set -- $cfg
    "$bin/bench_attitude_error" "${drives[@]}" --tilt-window "$1" --tilt-weighting "$2" \
      --tilt-moves-height "$3" | sed -n 3p
  done
} > "$doc"
cat "$doc"
