#!/usr/bin/env bash
# e2e (issue 19) for simulate, simulate-lidar and lsm-build: a failed run (a folder where one of
# its outputs goes, found only after the computation) exits 4 naming that file and leaves every
# output of the previous run byte-identical, with no temporary file left; a locked output folder
# is refused at once (exit 4); an output path below a regular file is refused before any work.
# A poses file lsm-build would not use (a drive with OXTS, or --egomotion imu_wheel) is refused
# (exit 2) naming the file instead of being ignored.
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
for tool in simulate simulate-lidar lsm-build; do
  [[ -x "$BIN/$tool" ]] || { echo "SKIP: $tool not built"; exit 77; }
done
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
cd "$TMP"
fail() { echo "FAIL: $*"; exit 1; }
snapshot() { (cd "$1" && find . -type f ! -name '.mapfuse.lock' -print0 | sort -z | xargs -0 sha1sum); }

# check TOOL OUT VICTIM CMD...: CMD writes into OUT; VICTIM is one of its outputs (relative).
check() {
  local tool=$1 out=$2 victim=$3; shift 3
  "$@" >/dev/null 2>&1 || fail "$tool: first run failed"
  [[ -f "$out/$victim" ]] || fail "$tool: $out/$victim not written"
  rm "$out/$victim" && mkdir "$out/$victim"
  local before; before=$(snapshot "$out")
  local rc=0; "$@" >/dev/null 2>err.txt || rc=$?
  [[ $rc == 4 ]] || { cat err.txt; fail "$tool: a folder in an output's place gave exit $rc, not 4"; }
  grep -qF "$victim" err.txt || { cat err.txt; fail "$tool: the message does not name $victim"; }
  [[ "$(snapshot "$out")" == "$before" ]] || fail "$tool: a failed run changed earlier outputs"
  [[ -z "$(find "$out" -name '*.tmp-*')" ]] || fail "$tool: temporary files left behind"
  rmdir "$out/$victim"
  flock "$out/.mapfuse.lock" sleep 5 & local holder=$!
  sleep 0.3
  rc=0; "$@" >/dev/null 2>err.txt || rc=$?
  kill $holder 2>/dev/null || true; wait $holder 2>/dev/null || true
  [[ $rc == 4 ]] || { cat err.txt; fail "$tool: a locked output folder gave exit $rc, not 4"; }
  grep -q "another mapfuse run" err.txt || { cat err.txt; fail "$tool: lock message"; }
  echo "output_sets_vehicle: $tool ok"
}

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
