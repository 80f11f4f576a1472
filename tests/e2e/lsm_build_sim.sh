#!/usr/bin/env bash
# e2e: simulate --level frames -> lsm-build (observations and masks) -> info -> georef.
# Checks that lsm-build's LSMs are read by the downstream tools and that bad input fails
# with the documented exit code.
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
for tool in simulate lsm-build; do
  [[ -x "$BIN/$tool" ]] || { echo "SKIP: $tool not built"; exit 77; }
done
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

"$BIN/simulate" -o "$TMP/sim" --level frames --traversals 2 --route-length 250 --seed 3 --quiet > /dev/null
n=0
for drive in "$TMP"/sim/frames/*; do
  lsm="$("$BIN/lsm-build" "$drive" -o "$TMP/lsm" --quiet)"
  [[ -f "$lsm" ]] || { echo "FAIL: lsm-build printed '$lsm' which does not exist"; exit 1; }
  n=$((n + 1))
done
[[ $n -eq 2 ]] || { echo "FAIL: expected 2 drives, got $n"; exit 1; }
first="$(ls -d "$TMP"/sim/frames/* | head -1)"
"$BIN/lsm-build" "$first" -o "$TMP/masks" --semantics masks --render false --quiet > /dev/null

if [[ -x "$BIN/info" ]]; then
  "$BIN/info" "$TMP"/lsm/*.lsm.json > "$TMP/info.jsonl"
  [[ $(wc -l < "$TMP/info.jsonl") -eq 2 ]] || { echo "FAIL: info did not describe 2 LSMs"; exit 1; }
fi
if [[ -x "$BIN/georef" ]]; then
  "$BIN/georef" "$TMP"/lsm/*.lsm.json -o "$TMP/enu" --quiet > /dev/null
  [[ $(ls "$TMP"/enu/*.lsm.json | wc -l) -eq 2 ]] || { echo "FAIL: georef wrote no LSMs"; exit 1; }
fi

# Bad input: missing calibration -> exit 4; broken observations -> exit 3.
cp -r "$first" "$TMP/bad"
rm "$TMP/bad/calibration.json"
set +e
"$BIN/lsm-build" "$TMP/bad" -o "$TMP/badout" --quiet > /dev/null 2>&1; rc=$?
set -e
[[ $rc -eq 4 ]] || { echo "FAIL: missing calibration gave exit $rc, expected 4"; exit 1; }
cp -r "$first" "$TMP/bad2"
echo '{"frame": 0, "stamp": "x"}' >> "$TMP/bad2/observations.jsonl"
set +e
"$BIN/lsm-build" "$TMP/bad2" -o "$TMP/badout" --quiet > /dev/null 2>&1; rc=$?
set -e
[[ $rc -eq 3 ]] || { echo "FAIL: malformed observations gave exit $rc, expected 3"; exit 1; }
echo "OK"
