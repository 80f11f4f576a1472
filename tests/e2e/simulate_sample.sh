#!/usr/bin/env bash
# e2e: the embedded simulator scenario runs, writes LSMs + ground truth, and is deterministic;
# the Lanelet2 Karlsruhe map runs too (skipped when ../shared is absent).
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
SRC="${MAPFUSE_SOURCE_DIR:?}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
for run in a b; do
  "$BIN/simulate" --config "$SRC/samples/simulate/scenario.json" --traversals 4 -o "$TMP/$run" -q > "$TMP/$run.stdout"
done
test "$(ls "$TMP/a/lsm" | wc -l)" -eq 4
test -s "$TMP/a/truth/vector_map.json"
test -s "$TMP/a/truth/vector_map.geojson"
test -s "$TMP/a/simulate.summary.json"
(cd "$TMP/a" && find . -type f | sort | xargs sha256sum) > "$TMP/a.sums"
(cd "$TMP/b" && find . -type f | sort | xargs sha256sum) > "$TMP/b.sums"
diff "$TMP/a.sums" "$TMP/b.sums"
# Frames level on a short route.
"$BIN/simulate" --level frames --traversals 1 --route-length 100 -o "$TMP/f" -q > /dev/null
test -s "$(ls -d "$TMP"/f/frames/*)/observations.jsonl"
MAP="${MAPFUSE_SHARED:-$SRC/../shared}/data/maps/lanelet2_karlsruhe_mapping_example.osm"
if [ ! -f "$MAP" ]; then echo "SKIP: $MAP absent"; exit 77; fi
"$BIN/simulate" --map "$MAP" --traversals 3 --route-length 400 -o "$TMP/k" -q > /dev/null
test "$(ls "$TMP/k/lsm" | wc -l)" -eq 3
echo "simulate e2e ok"
