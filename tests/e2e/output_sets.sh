#!/usr/bin/env bash
# e2e (issue 19): a run's outputs are replaced as a set. For each tool: a failed run (a folder
# where one of its outputs goes, found only after the computation) exits 4 naming that file and
# leaves every output of the previous run byte-identical, with no temporary file left; a second
# run on a locked output folder is refused at once (exit 4); an output path below a regular file
# is refused before any work (exit 4). Duplicate inputs are refused (exit 2) naming both.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
source "$HERE/lib/scratch.sh"  # BIN; TMP, the working folder
NAME=output_sets
source "$HERE/lib/output_set_check.sh"

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
