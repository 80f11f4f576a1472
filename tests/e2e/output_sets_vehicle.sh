#!/usr/bin/env bash
# e2e (issue 19) for simulate, simulate-lidar and lsm-build: a failed run (a folder where one of
# its outputs goes, found only after the computation) exits 4 naming that file and leaves every
# output of the previous run byte-identical, with no temporary file left; a locked output folder
# is refused at once (exit 4); an output path below a regular file is refused before any work.
# A poses file lsm-build would not use (a drive with OXTS, or --egomotion imu_wheel) is refused
# (exit 2) naming the file instead of being ignored.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
BIN="${MAPFUSE_BIN_DIR:?}"
for tool in simulate simulate-lidar lsm-build; do
  [[ -x "$BIN/$tool" ]] || { echo "SKIP: $tool not built"; exit 77; }
done
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
cd "$TMP"
NAME=output_sets_vehicle
source "$HERE/lib/output_set_check.sh"

check simulate sim truth/vector_map.geojson \
  "$BIN/simulate" -q --level frames --traversals 1 --route-length 200 --seed 3 -o sim
drive=$(ls -d sim/frames/* | head -1)
id=$(basename "$drive")
check lsm-build lsm "$id.bev.png" "$BIN/lsm-build" -q "$drive" -o lsm
lidar_drive=2011_09_26/2011_09_26_drive_0001_sync
check simulate-lidar lidar "$lidar_drive/simulate-lidar.config.json" \
  "$BIN/simulate-lidar" -q --frames 2 --azimuth-steps 300 -o lidar

# an output folder below a regular file: refused before any work
touch afile
for cmd in "lsm-build -q $drive" "simulate -q --traversals 1" "simulate-lidar -q --frames 2"; do
  rc=0; $BIN/$cmd -o afile/out >/dev/null 2>err.txt || rc=$?
  [[ $rc == 4 ]] || { cat err.txt; fail "$cmd below a regular file gave exit $rc, not 4"; }
done

# a poses file that would not be used is refused, naming it (not ignored)
rc=0; "$BIN/lsm-build" -q "lidar/$lidar_drive" --poses nope.txt -o lsm_oxts >/dev/null 2>err.txt || rc=$?
[[ $rc == 2 || $rc == 3 ]] || { cat err.txt; fail "--poses on an OXTS drive gave exit $rc"; }
grep -q "nope.txt" err.txt || { cat err.txt; fail "--poses refusal does not name the file"; }
[[ ! -e lsm_oxts/lsm-build.summary.json ]] || fail "--poses refused but a summary was written"
rc=0; "$BIN/lsm-build" -q "$drive" --egomotion imu_wheel --poses nope.txt -o lsm_imu \
  >/dev/null 2>err.txt || rc=$?
[[ $rc == 2 ]] && grep -q "nope.txt" err.txt || { cat err.txt; fail "--poses with imu_wheel gave $rc"; }
echo "output_sets_vehicle: ok"
