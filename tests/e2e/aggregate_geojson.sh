#!/usr/bin/env bash
# simulate -> georef -> aggregate -> evaluate map on a small world; the GeoJSON must open in
# GDAL's ogrinfo without warnings and the OSM must be XML with line_thin ways.
set -euo pipefail
bin="$MAPFUSE_BIN_DIR"
if ! command -v ogrinfo >/dev/null; then
  echo "SKIP: ogrinfo (gdal-bin) not installed"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin/simulate" -q --traversals 4 --route-length 600 -o "$tmp/sim" >/dev/null
"$bin/georef" -q --origin 49.0,8.4,110 -o "$tmp/geo" "$tmp"/sim/lsm/*.lsm.cbor >/dev/null
ls "$tmp"/geo/*.lsm.cbor > "$tmp/list.txt"
"$bin/aggregate" -q --discrete-min-pts 2 --lane-min-pts 2 -o "$tmp/agg" "@$tmp/list.txt" >/dev/null
for f in map.cbor map.json map.geojson map.osm map.png aggregate.summary.json; do
  test -s "$tmp/agg/$f" || { echo "missing $f" >&2; exit 1; }
done
out=$(ogrinfo -ro -al -so "$tmp/agg/map.geojson" 2>&1)
echo "$out" | grep -q "Feature Count" || { echo "$out" >&2; exit 1; }
if echo "$out" | grep -qiE "warning|error"; then
  echo "ogrinfo complained:" >&2
  echo "$out" >&2
  exit 1
fi
grep -q "k=\"type\" v=\"line_thin\"" "$tmp/agg/map.osm"
"$bin/evaluate" map -q --map "$tmp/agg/map.cbor" --truth "$tmp/sim/truth/vector_map.json" \
  --truth-trajectories "$tmp/sim/truth" --lsm "$tmp"/geo/*.lsm.cbor -o "$tmp/eval" >/dev/null
for f in evaluate.summary.json evaluate.md error_per_class.png map_over_truth.png; do
  test -s "$tmp/eval/$f" || { echo "missing $f" >&2; exit 1; }
done
grep -q "| lane_line |" "$tmp/eval/evaluate.md"
grep -q "## Trajectories" "$tmp/eval/evaluate.md"
echo "aggregate_geojson: ok"
