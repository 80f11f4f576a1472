#!/usr/bin/env bash
# e2e (issue 37): no tool writes into what it reads. For every tool with -o, an output equal to,
# inside, or containing one of its inputs (also through a symbolic link, `..`, an @list or a
# stdin list) is refused with exit 2 before any work, naming both paths, and every input is left
# byte-identical (checksums of the whole scratch tree before and after). docs/cli.md "Outputs
# never overlap inputs".
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
source "$HERE/lib/scratch.sh"  # BIN; TMP, the working folder
fail() { echo "output_over_input: $*" >&2; exit 1; }
sums() { find . -type f ! -name err.txt -print0 | sort -z | xargs -0 sha256sum; }

"$BIN/simulate" -q --traversals 2 --route-length 300 -o sim >/dev/null
"$BIN/georef" -q -o geo sim/lsm/*.cbor >/dev/null
"$BIN/tile" -q --tile-size 200 -o tiles geo/*.cbor >/dev/null
"$BIN/aggregate" -q --discrete-min-pts 2 --lane-min-pts 2 -o agg geo/*.cbor >/dev/null
drive=$("$BIN/simulate-lidar" -q -o lidar --seed 3 --frames 3 --azimuth-steps 500)
drive=${drive#"$TMP/"}
ln -s geo geo_link
ls geo/*.cbor > list.txt
tile0=$(python3 -c 'import json;print(json.load(open("tiles/tiles.json"))["tiles"][0]["name"])')
cp "$MAPFUSE_SOURCE_DIR/configs/simulate-lidar.json" lidar/sl.json
n=0
# refused WHAT_OUT CMD...: exit 2, the message names the -o path, inputs unchanged
refused() {
  local out=$1; shift
  local before; before=$(sums)
  local rc=0; "$@" >/dev/null 2>err.txt </dev/null || rc=$?
  [[ $rc == 2 ]] || { cat err.txt; fail "$* gave exit $rc, not 2"; }
  grep -q "never writes into what it reads" err.txt && grep -qF "'$out'" err.txt \
    || { cat err.txt; fail "$*: message does not name the output"; }
  [[ "$(sums)" == "$before" ]] || fail "$*: an input changed"
  n=$((n + 1))
}
refused geo "$BIN/align" -q -o geo geo/*.cbor                       # -o is the input folder
refused geo_link "$BIN/align" -q -o geo_link geo/*.cbor             # ... through a link
refused geo/../geo "$BIN/align" -q -o geo/../geo @list.txt          # ... through .. and @list
refused sim/lsm "$BIN/georef" -q -o sim/lsm sim/lsm/*.cbor
refused . "$BIN/aggregate" -q -o . geo/*.cbor                       # contains the inputs
refused geo "$BIN/tile" -q -o geo geo/*.cbor
refused tiles "$BIN/balance" -q --tiles tiles/tiles.json -o tiles
refused "tiles/$tile0/out" "$BIN/balance" -q --tiles tiles/tiles.json -o "tiles/$tile0/out"
refused agg/map.cbor "$BIN/stitch" -q --tiles tiles/tiles.json -o agg/map.cbor agg/map.cbor
refused geo "$BIN/localize" -q --map sim/truth/vector_map.json -o geo geo/*.cbor
refused sim/truth "$BIN/localize" -q --map sim/truth/vector_map.json -o sim/truth geo/*.cbor
refused sim "$BIN/simulate" -q --map sim/truth/vector_map.json -o sim
refused lidar "$BIN/simulate-lidar" -q --config lidar/sl.json -o lidar
refused "$drive" "$BIN/lidar-semantic-map" -q "$drive" -o "$drive"   # labels are the truth
refused "$drive/out" "$BIN/lidar-semantic-map" -q "$drive" -o "$drive/out"
refused "$drive" "$BIN/lidar-semantic-map" train -q "$drive" -o "$drive"
refused "$drive" "$BIN/lsm-build" -q "$drive" -o "$drive"
refused agg "$BIN/evaluate" map -q --map agg/map.cbor --truth sim/truth/vector_map.json -o agg
refused agg "$BIN/update" -q --map agg/map.json -o agg geo/*.cbor    # the map's folder
refused geo "$BIN/update" -q --map agg/map.json -o geo geo/*.cbor    # the new drives' folder
refused "$drive/labels" "$BIN/evaluate" voxels -q --drive "$drive" \
  --predicted-labels "$drive/labels" -o "$drive/labels"
# a list on stdin is known only once read: still refused before any work
before=$(sums); rc=0
"$BIN/align" -q -o geo - < list.txt >/dev/null 2>err.txt || rc=$?
[[ $rc == 2 && "$(sums)" == "$before" ]] || { cat err.txt; fail "align stdin list gave $rc"; }
# a sibling whose name starts like an input is not inside it (whole path components)
"$BIN/tile" -q --tile-size 200 -o geo_tiles geo/*.cbor >/dev/null \
  || fail "tile -o geo_tiles beside geo/ was refused"
echo "output_over_input: $((n + 1)) refusals ok, sibling output accepted"
