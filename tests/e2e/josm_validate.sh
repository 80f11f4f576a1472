#!/usr/bin/env bash
# JOSM's validator on the Lanelet2 export (issue 35): the aggregated map.osm of the README
# demo's world (samples/demo/crowd-frames.json, seed 2, LSM level, scripts/crowd.mk) has no
# issue of severity "Errors" in `josm validate` (Debian package josm, headless). Its warnings
# (decimal places of `ele`, `color` rather than OSM's `colour`: Lanelet2's own tag) are listed
# in docs/formats.md "What JOSM says". Skips (77) where josm is not installed (about 2 minutes
# of apt-get, so not part of scripts/install-deps.sh).
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
SRC="${MAPFUSE_SOURCE_DIR:?}"
command -v josm >/dev/null || { echo "SKIP: josm not installed (apt-get install josm)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
source "$SRC/tests/e2e/lib/scratch.sh"
export HOME="$PWD/home"  # JOSM keeps preferences and caches below HOME; the scratch folder's
mkdir -p "$HOME"

"$BIN/simulate" -q --config "$SRC/samples/demo/crowd-frames.json" --seed 2 --level lsm \
  -o sim >/dev/null
make -s -j2 -f "$SRC/scripts/crowd.mk" BIN="$BIN" LSM_DIR=sim/lsm WORK=crowd map >/dev/null
osm=crowd/aggregate/map.osm
test -s "$osm" || fail "no map.osm"
timeout 600 josm validate -i "$osm" -o josm.geojson > josm.log 2>&1 ||
  { tail -20 josm.log; fail "josm validate did not run"; }
test -s josm.geojson || { tail -20 josm.log; fail "josm wrote no report"; }
# One GeoJSON FeatureCollection per line (MapRoulette's form); count by severity.
python3 - josm.geojson <<'PY' || fail "JOSM reports errors on $osm"
import collections, json, sys
by = collections.Counter()
errors = collections.Counter()
for line in open(sys.argv[1]):
    line = line.strip().lstrip("\x1e")
    if not line:
        continue
    for f in json.loads(line)["features"]:
        p = f["properties"]
        by[p.get("severity")] += 1
        if p.get("severity") == "Errors":
            errors[(p.get("message"), p.get("description"))] += 1
print("JOSM issues by severity:", dict(by))
for (msg, desc), n in errors.most_common():
    print(f"  {n}x error: {msg} ({desc})")
sys.exit(1 if errors else 0)
PY
echo "PASS"
