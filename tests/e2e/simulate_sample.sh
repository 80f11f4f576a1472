#!/usr/bin/env bash
# e2e: the simulator sample scenario (samples/simulate/scenario.json) runs, writes LSMs + ground
# truth, and is deterministic at the LSM and at the frames level; the Lanelet2 Karlsruhe map
# runs too (skipped when ../shared is absent).
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
SRC="${MAPFUSE_SOURCE_DIR:?}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
sums() { (cd "$1" && find . -type f ! -name .mapfuse.lock | sort | xargs sha256sum); }
fail() { echo "FAIL: $*" >&2; exit 1; }
for run in a b; do
  "$BIN/simulate" --config "$SRC/samples/simulate/scenario.json" --traversals 4 -o "$TMP/$run" -q > "$TMP/$run.stdout"
done
test "$(ls "$TMP/a/lsm" | wc -l)" -eq 4
test -s "$TMP/a/truth/vector_map.json"
test -s "$TMP/a/truth/vector_map.geojson"
test -s "$TMP/a/simulate.summary.json"
sums "$TMP/a" > "$TMP/a.sums"
sums "$TMP/b" > "$TMP/b.sums"
diff "$TMP/a.sums" "$TMP/b.sums"
# Frames level on short routes: one seed gives byte-identical trees (every file, PNG masks
# included, two traversals simulated in parallel); another seed gives different bytes.
for run in fa fb; do
  "$BIN/simulate" --level frames --seed 42 --traversals 2 --route-length 100 -o "$TMP/$run" -q > /dev/null
done
"$BIN/simulate" --level frames --seed 7 --traversals 2 --route-length 100 -o "$TMP/fc" -q > /dev/null
for run in fa fb fc; do sums "$TMP/$run" > "$TMP/$run.sums"; done
test "$(ls -d "$TMP"/fa/frames/* | wc -l)" -eq 2
for d in "$TMP"/fa/frames/*; do test -s "$d/observations.jsonl"; done
test "$(grep -c '/masks/.*\.png$' "$TMP/fa.sums")" -gt 100
diff "$TMP/fa.sums" "$TMP/fb.sums"
if cmp -s "$TMP/fa.sums" "$TMP/fc.sums"; then fail "seeds 42 and 7 gave identical frames"; fi
if cmp -s <(grep '\.png$' "$TMP/fa.sums") <(grep '\.png$' "$TMP/fc.sums"); then
  fail "seeds 42 and 7 gave identical masks"
fi
MAP="${MAPFUSE_SHARED:-$SRC/../shared}/data/maps/lanelet2_karlsruhe_mapping_example.osm"
if [ ! -f "$MAP" ]; then echo "SKIP: $MAP absent"; exit 77; fi
"$BIN/simulate" --map "$MAP" --traversals 3 --route-length 400 -o "$TMP/k" -q > /dev/null
test "$(ls "$TMP/k/lsm" | wc -l)" -eq 3
echo "simulate e2e ok"
