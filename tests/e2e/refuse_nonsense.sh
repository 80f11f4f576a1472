#!/usr/bin/env bash
# e2e (issues 35, 37): command-line habits and inputs that make no sense. Every tool answers
# --version (exit 0) and, without arguments, an error in the `<tool>: error: ...` form (exit 2);
# a missing --tiles file is exit 4 (docs/cli.md); a device given as a document is refused naming
# it (exit 4, not a 2 GB read); stitch checks its maps against tiles.json (a tile without its
# map, the same map twice, a map of no tile: exit 2; a tile core that is not the grid's: exit 3);
# balance without tiles is exit 3; evaluate map warns about an empty truth and a truth 2 km
# away (a 'problems' line in the summary) and with --strict refuses them (exit 3); localize on
# a map 2 km away names the drive and the cause (outside the map, not no markings).
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
source "$HERE/lib/scratch.sh"  # BIN; TMP, the working folder
fail() { echo "refuse_nonsense: $*" >&2; exit 1; }
# expect CODE PATTERN CMD...: exit CODE and one stderr line matching PATTERN
expect() {
  local code=$1 pattern=$2; shift 2
  local rc=0; timeout 60 "$@" >out.txt 2>err.txt </dev/null || rc=$?
  [[ $rc == "$code" ]] || { cat err.txt; fail "$* gave exit $rc, not $code"; }
  grep -qE "$pattern" err.txt || { cat err.txt; fail "$*: stderr lacks /$pattern/"; }
}

for tool in aggregate align balance evaluate georef info lidar-semantic-map localize lsm-build \
  simulate simulate-lidar stitch tile; do
  "$BIN/$tool" --version >out.txt || fail "$tool --version failed"
  grep -qE '^mapfuse [0-9]+\.[0-9]+\.[0-9]+' out.txt || fail "$tool --version: $(cat out.txt)"
  expect 2 "^$tool: error: " "$BIN/$tool"
done
expect 4 "^balance: error: nope/tiles.json: " "$BIN/balance" --tiles nope/tiles.json -o b
expect 4 "^stitch: error: nope/tiles.json: " "$BIN/stitch" --tiles nope/tiles.json -o s/m.cbor x
ln -s /dev/zero zero.cbor
expect 4 "zero.cbor: is not a regular file" "$BIN/info" zero.cbor

"$BIN/simulate" -q --traversals 2 --route-length 300 -o sim >/dev/null
"$BIN/georef" -q -o geo sim/lsm/*.cbor >/dev/null
"$BIN/tile" -q --tile-size 200 -o tiles geo/*.cbor >/dev/null
for t in tiles/tile_*; do
  "$BIN/aggregate" -q --discrete-min-pts 2 --lane-min-pts 2 -o "$t/aggregate" "$t"/*.cbor >/dev/null
done
maps=(tiles/tile_*/aggregate/map.cbor)
[[ ${#maps[@]} -ge 2 ]] || fail "expected several tiles, got ${#maps[@]}"
"$BIN/stitch" -q --tiles tiles/tiles.json -o st/map.cbor "${maps[@]}" >/dev/null
expect 2 "has no map among" "$BIN/stitch" -q --tiles tiles/tiles.json -o st2/map.cbor "${maps[@]:1}"
expect 2 "given twice" "$BIN/stitch" -q --tiles tiles/tiles.json -o st2/map.cbor "${maps[@]}" \
  "${maps[0]}"
mkdir -p other && cp "${maps[0]}" other/map.cbor
expect 2 "names a tile of" "$BIN/stitch" -q --tiles tiles/tiles.json -o st2/map.cbor \
  "${maps[@]}" other/map.cbor
[[ ! -e st2 ]] || fail "a refused stitch created its output folder"
edit() {  # edit SRC DST PYTHON: DST = tiles.json SRC changed by the python statement on d
  python3 -c "import json,sys; d=json.load(open('$1')); $3; json.dump(d, open('$2','w'))"
}
edit tiles/tiles.json tiles/core_text.json 'd["tiles"][0]["core"] = ["a", "b", "c", "d"]'
expect 3 "core_text.json.*core" "$BIN/stitch" -q --tiles tiles/core_text.json -o st2/map.cbor \
  "${maps[@]}"
edit tiles/tiles.json tiles/core_moved.json 'd["tiles"][0]["core"][0] += 50'
expect 3 "core_moved.json.*is not the grid" "$BIN/stitch" -q --tiles tiles/core_moved.json \
  -o st2/map.cbor "${maps[@]}"
edit tiles/tiles.json tiles/none.json 'd["tiles"] = []'
expect 3 "none.json: field 'tiles': no tiles" "$BIN/balance" -q --tiles tiles/none.json -o bal

# evaluate map: an empty truth and a truth 2 km away are warned about, or refused with --strict.
"$BIN/aggregate" -q --discrete-min-pts 2 --lane-min-pts 2 -o agg geo/*.cbor >/dev/null
t=sim/truth/vector_map.json
edit $t empty.json 'd["instances"] = []'
python3 - "$t" far.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for i in d["instances"]:
    for p in i["points"]:
        p[0] += 2000.0
json.dump(d, open(sys.argv[2], "w"))
PY
"$BIN/evaluate" map -q --map agg/map.cbor --truth $t -o ev_ok >/dev/null
python3 -c "import json,sys; sys.exit(json.load(open('ev_ok/evaluate.summary.json'))['problems'] != [])" \
  || fail "the true map was reported as a problem"
for truth in empty.json far.json; do
  rc=0; "$BIN/evaluate" map --map agg/map.cbor --truth $truth -o ev_$truth >/dev/null 2>err.txt \
    || rc=$?
  [[ $rc == 0 ]] || { cat err.txt; fail "evaluate map on $truth gave exit $rc"; }
  grep -q "$truth" err.txt || { cat err.txt; fail "no warning naming $truth"; }
  python3 -c "import json,sys; p=json.load(open('ev_$truth/evaluate.summary.json'))['problems']; sys.exit(not any('$truth' in x for x in p))" \
    || fail "summary of $truth lists no problem"
  expect 3 "$truth.*strict" "$BIN/evaluate" map -q --strict true --map agg/map.cbor \
    --truth $truth -o evs_$truth
done
grep -q "do not overlap" "ev_far.json/evaluate.summary.json" || fail "far truth: no overlap reason"

# localize on a map 2 km away: every keyframe lost, the message names the drives and the cause.
lsm0=$(ls geo/*.cbor | head -1)
expect 3 "$lsm0: [0-9]+ of [0-9]+ keyframes lost \\(0 no markings to match.*outside the map" \
  "$BIN/localize" -q --map far.json -o loc "$lsm0"
echo "refuse_nonsense: ok"
