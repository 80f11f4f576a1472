#!/usr/bin/env bash
# e2e (issue 19): a run's outputs are replaced as a set. For each tool: a failed run (a folder
# where one of its outputs goes, found only after the computation) exits 4 naming that file and
# leaves every output of the previous run byte-identical, with no temporary file left; a second
# run on a locked output folder is refused at once (exit 4); an output path below a regular file
# is refused before any work (exit 4). Duplicate inputs are refused (exit 2) naming both.
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
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
  # a second run while another holds the folder's lock
  flock "$out/.mapfuse.lock" sleep 5 & local holder=$!
  sleep 0.3
  rc=0; "$@" >/dev/null 2>err.txt || rc=$?
  kill $holder 2>/dev/null || true; wait $holder 2>/dev/null || true
  [[ $rc == 4 ]] || { cat err.txt; fail "$tool: a locked output folder gave exit $rc, not 4"; }
  grep -q "another mapfuse run" err.txt || { cat err.txt; fail "$tool: lock message"; }
  echo "output_sets: $tool ok"
}

"$BIN/simulate" -q --traversals 3 --route-length 400 -o sim >/dev/null
lsms=(sim/lsm/*.cbor)
check georef geo "$(basename "${lsms[1]}")" "$BIN/georef" -q -o geo "${lsms[@]}"
check align al "$(basename "${lsms[2]}")" "$BIN/align" -q -o al geo/*.cbor
check aggregate agg map.geojson "$BIN/aggregate" -q -o agg al/*.cbor
check evaluate ev error_per_class.png "$BIN/evaluate" map -q --map agg/map.cbor \
  --truth sim/truth/vector_map.json -o ev

# an output folder below a regular file: refused before any work
touch afile
rc=0; "$BIN/align" -q -o afile/out geo/*.cbor >/dev/null 2>err.txt || rc=$?
[[ $rc == 4 ]] || { cat err.txt; fail "align below a regular file gave exit $rc, not 4"; }

# duplicate inputs: the same file twice, or one drive under two names (exit 2, both named)
cp "${lsms[0]}" copy.cbor
for tool in georef align aggregate; do
  in=("${lsms[@]}"); [[ $tool != georef ]] && in=(geo/*.cbor)
  rc=0; "$BIN/$tool" -q -o dup "${in[0]}" "${in[@]}" >/dev/null 2>err.txt || rc=$?
  [[ $rc == 2 ]] && grep -q "same file" err.txt || { cat err.txt; fail "$tool: same file twice gave $rc"; }
done
rc=0; "$BIN/georef" -q -o dup "${lsms[0]}" copy.cbor >/dev/null 2>err.txt || rc=$?
[[ $rc == 2 ]] && grep -q "same drive" err.txt && grep -q copy.cbor err.txt \
  || { cat err.txt; fail "georef: one drive under two names gave $rc"; }
echo "output_sets: ok"
