#!/usr/bin/env bash
# The whole crowd chain on a real OpenDRIVE map (issue 20): MONAEast.xodr (RoadRunner export of a
# Munich district, ../shared/data/maps) -> simulate (N traversals) -> scripts/crowd.mk (georef,
# align gba_sgicp, aggregate) -> evaluate map. Writes docs/performance-opendrive.md (the world,
# the drives, the map and evaluate's table). Usage: scripts/bench/bench_opendrive.sh [BIN] [N]
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"  # root, bin, tmp (removed on exit), load
n=${2:-20}
shared=$(realpath -m "${MAPFUSE_SHARED:-$root/../shared}")
xodr="$shared/data/maps/MONAEast.xodr"
if [[ ! -f "$xodr" ]]; then echo "bench_opendrive: $xodr absent, skipped" >&2; exit 0; fi
sim_cmd=("$bin/simulate" -q --map "$xodr" --traversals "$n" --route-length 800 -o "$tmp/sim")
"${sim_cmd[@]}" > /dev/null
t0=$(date +%s.%N)
make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$tmp/sim/lsm" WORK="$tmp/work" \
  TRUTH="$tmp/sim/truth/vector_map.json" TRUTH_TRAJ="$tmp/sim/truth" > /dev/null
t1=$(date +%s.%N)
python3 - "$tmp" "$n" "$load" "$(awk "BEGIN { print $t1 - $t0 }")" "$root/docs/performance-opendrive.md" <<'PY'
import datetime, json, sys
tmp, n, load, seconds, out = sys.argv[1:]
sim = json.load(open(f"{tmp}/sim/simulate.summary.json"))
agg = json.load(open(f"{tmp}/work/aggregate/aggregate.summary.json"))
ev = open(f"{tmp}/work/evaluate/evaluate.md").read().split("\n", 1)[1].strip()
ws = sim["world_stats"]
# The corpus and long-road section (scripts/bench/bench_opendrive_corpus.sh) is kept.
import os
old = open(out).read() if os.path.exists(out) else ""
kept = old[old.find("<!-- corpus:begin -->"):] if "<!-- corpus:begin -->" in old else ""
with open(out, "w") as f:
    f.write(f"""# OpenDRIVE: the crowd chain on MONAEast.xodr

Measured by `scripts/bench/bench_opendrive.sh` on {datetime.date.today()} (load average at start
{load}). Commands:

```sh
simulate --map ../shared/data/maps/MONAEast.xodr --traversals {n} --route-length 800 -o sim
make -j2 -f scripts/crowd.mk LSM_DIR=sim/lsm WORK=work TRUTH=sim/truth/vector_map.json TRUTH_TRAJ=sim/truth
```

World (OpenDRIVE 1.4, RoadRunner, georeference `+proj=tmerc +lat_0=48.17722803371593
+lon_0=11.59292664305758`, origin = that point): {int(ws['roads'])} roads, {int(ws['junctions'])}
junctions, {sim['lanes']} lanes ({sim['lane_km']:.2f} lane km; {int(ws['lanes_with_successor'])}
with a successor, {int(ws['lane_links'])} lane links, {int(ws['lane_links_rejected'])} rejected),
{int(ws['lane_lines'])} lane lines ({sim['lane_line_km']:.2f} km; {int(ws['line_pieces_joined'])}
pieces joined, {int(ws['road_marks_not_lines'])} road marks that are no painted line),
elements by class {json.dumps(sim['elements_by_class'])}.
Drives: {sim['drives']} traversals, {sim['km_driven']:.1f} km driven.
Map: {agg['instances']} instances, {agg['size']['kb_per_km']:.1f} KB/km, Lanelet2 export
{agg['lanelet2']['lanelets']} lanelets ({agg['lanelet2']['lanelets_direction_known']} one-way).
Chain (georef, align, aggregate, evaluate): {float(seconds):.1f} s.

{ev}
""")
    if kept: f.write("\n" + kept)
PY
echo "bench_opendrive: docs/performance-opendrive.md written" >&2
