#!/usr/bin/env bash
# Maps in and out that real tools accept (issue 20), on the README demo's map (samples/demo:
# simulate raw frames -> lsm-build -> georef -> align -> aggregate, scripts/crowd.mk):
#  - map.osm (Lanelet2) reads in osmium (fileinfo -e, check-refs -r) and GDAL's ogrinfo with no
#    error or warning;
#  - map.geojson and the truth's GeoJSON are valid under GEOS with counter-clockwise exteriors
#    (scripts/check-geojson.py, Debian's python3-shapely).
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
SRC="${MAPFUSE_SOURCE_DIR:?}"
fail() { echo "FAIL: $*"; exit 1; }
for tool in osmium ogrinfo; do
  command -v "$tool" >/dev/null || fail "$tool missing (scripts/install-deps.sh)"
done
/usr/bin/python3 -c "import shapely" 2>/dev/null || fail "python3-shapely missing (scripts/install-deps.sh)"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

"$BIN/simulate" -q --config "$SRC/samples/demo/crowd-frames.json" -o "$TMP/sim" >/dev/null
make -s -j2 -f "$SRC/scripts/crowd.mk" BIN="$BIN" FRAMES_DIR="$TMP/sim/frames" WORK="$TMP/crowd" \
  map >/dev/null
osm="$TMP/crowd/aggregate/map.osm"
test -s "$osm" || fail "no map.osm"

# osmium: the file parses, every referenced node / way / relation exists.
osmium fileinfo -e "$osm" > "$TMP/fileinfo.txt" 2>&1 || { cat "$TMP/fileinfo.txt"; fail "osmium fileinfo"; }
grep -q "Number of relations: [1-9]" "$TMP/fileinfo.txt" || { cat "$TMP/fileinfo.txt"; fail "no relations"; }
osmium check-refs -r "$osm" > "$TMP/refs.txt" 2>&1 || { cat "$TMP/refs.txt"; fail "osmium check-refs"; }
# GDAL's OSM driver: every layer opens without error or warning (negative ids, as JOSM and
# Lanelet2 write new elements, need its documented OSM_USE_CUSTOM_INDEXING=NO).
ogrinfo --config OSM_USE_CUSTOM_INDEXING NO -ro -al -so "$osm" > "$TMP/ogr.txt" 2>&1 || { cat "$TMP/ogr.txt"; fail "ogrinfo"; }
if grep -qiE "error|warning" "$TMP/ogr.txt"; then cat "$TMP/ogr.txt"; fail "ogrinfo complained"; fi
grep -q "Layer name: multipolygons\|Layer name: other_relations" "$TMP/ogr.txt" || fail "ogrinfo layers"
# Lanelets and regulatory elements are there.
grep -q "v=\"lanelet\"" "$osm" || fail "no lanelet relation"
grep -q "v=\"regulatory_element\"" "$osm" || fail "no regulatory element"

# GeoJSON: valid under GEOS, exteriors counter-clockwise.
/usr/bin/python3 "$SRC/scripts/check-geojson.py" "$TMP/crowd/aggregate/map.geojson" \
  "$TMP/sim/truth/vector_map.geojson" || fail "GeoJSON not valid"
echo "interop_formats: ok"
