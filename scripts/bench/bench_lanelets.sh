#!/usr/bin/env bash
# Lanelet2 export of the procedural 50-traversal map (issue 20): simulate --traversals 50, the
# crowd chain (scripts/crowd.mk: georef, align, aggregate), then
#  - bench_lanelets: share of the true lane length (where the map has lane lines on both sides)
#    inside lanelets with both bounds, and inside lanelets driven the lane's way;
#  - osmium (fileinfo -e, check-refs -r) and ogrinfo on map.osm: errors and warnings;
#  - scripts/check-geojson.py (GEOS) on map.geojson: invalid features, clockwise exteriors.
# Writes docs/performance-lanelets.md. Usage: scripts/bench/bench_lanelets.sh [BIN_DIR] [N]
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"  # root, bin, tmp (removed on exit), load
n=${2:-50}
"$bin/simulate" -q --traversals "$n" -o "$tmp/sim" >/dev/null
make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$tmp/sim/lsm" WORK="$tmp/work" \
  TRUTH="$tmp/sim/truth/vector_map.json" TRUTH_TRAJ="$tmp/sim/truth" >/dev/null
agg="$tmp/work/aggregate"
"$bin/bench_lanelets" --seed 42 --osm "$agg/map.osm" --map "$agg/map.json" > "$tmp/coverage.json"
osmium_errors=0
osmium fileinfo -e "$agg/map.osm" > "$tmp/fileinfo.txt" 2>&1 || osmium_errors=$((osmium_errors + 1))
osmium check-refs -r "$agg/map.osm" > "$tmp/refs.txt" 2>&1 || osmium_errors=$((osmium_errors + 1))
ogrinfo --config OSM_USE_CUSTOM_INDEXING NO -ro -al -so "$agg/map.osm" > "$tmp/ogr.txt" 2>&1 || true
ogr_problems=$(grep -ciE "error|warning" "$tmp/ogr.txt" || true)
/usr/bin/python3 "$root/scripts/check-geojson.py" "$agg/map.geojson" > "$tmp/geojson.txt" || true
python3 - "$tmp" "$n" "$load" "$osmium_errors" "$ogr_problems" "$root/docs/performance-lanelets.md" <<'PY'
import datetime, json, re, subprocess, sys
tmp, n, load, osmium_errors, ogr_problems, out = sys.argv[1:]
c = json.load(open(f"{tmp}/coverage.json"))
agg = json.load(open(f"{tmp}/work/aggregate/aggregate.summary.json"))
ll = agg["lanelet2"]
info = open(f"{tmp}/fileinfo.txt").read()
count = lambda what: re.search(rf"Number of {what}: (\d+)", info).group(1) if re.search(rf"Number of {what}: (\d+)", info) else "?"
geo = open(f"{tmp}/geojson.txt").read().strip().splitlines()[-1]
model = subprocess.run("lscpu | grep 'Model name' | sed 's/.*: *//'", shell=True,
                       capture_output=True, text=True).stdout.strip()
with open(out, "w") as f:
    f.write(f"""# Lanelet2 export of the procedural 50-traversal map

Measured by `scripts/bench/bench_lanelets.sh` on {datetime.date.today()} ({model}, load average
at start {load}; the figures are counts and lengths, independent of load).
Command: `simulate --traversals {n}` (procedural world, seed 42, default noise), then
`make -f scripts/crowd.mk` (georef, align gba_sgicp, aggregate), then `bench_lanelets` on
`aggregate/map.osm`: every true lane of the simulator's world is sampled every metre; a sample
counts where the map has a lane line within 1 m of both lane borders (a lanelet with both bounds
is possible there), and is covered when it lies inside a lanelet of map.osm (read back with the
project's Lanelet2 reader).

| quantity | value |
|---|---|
| true lane length sampled (all lanes, intersections included) | {c['true_lane_m'] / 1000:.2f} km |
| ... with map lane lines on both sides | {c['marked_m'] / 1000:.2f} km |
| **... inside a lanelet with both bounds** | **{100 * c['share']:.1f} %** (target >= 95 %) |
| ... inside a one-way lanelet driven the lane's way | {100 * c['directed_share']:.1f} % |
| ... inside one-way lanelets of the opposite direction only | {100 * c['reversed_m'] / max(c['marked_m'], 1e-9):.1f} % |
| lanelets (road) / one-way (direction from drives, a stop line or a neighbour) | {c['lanelets']} / {c['lanelets_one_way']} |
| ... one-way by a neighbour (right-hand traffic, docs/formats.md) | {ll['lanelets_oriented_by_neighbours']} |
| crosswalk lanelets / traffic light and sign regulatory elements | {ll['crosswalk_lanelets']} / {ll['regulatory_elements']} |
| right_of_way / all_way_stop elements | {ll['right_of_way_elements']} / {ll['all_way_stop_elements']} |
| lane-line length that bounds a lanelet | {100 * ll['lane_line_bound_share']:.1f} % |
| osmium fileinfo -e / check-refs -r failures | {osmium_errors} (nodes {count('nodes')}, ways {count('ways')}, relations {count('relations')}) |
| ogrinfo -al -so lines with "error" or "warning" | {ogr_problems} |
| GEOS check of map.geojson (scripts/check-geojson.py) | {geo.split(': ', 1)[1]} |
""")
print(json.dumps(c))
PY
echo "bench_lanelets: docs/performance-lanelets.md written" >&2
