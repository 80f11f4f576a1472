#!/usr/bin/env bash
# e2e (issue 20): the crowd chain on a real OpenDRIVE map. MONAEast.xodr (../shared/data/maps,
# skipped when absent) -> simulate (4 traversals) -> scripts/crowd.mk (georef, align, aggregate,
# evaluate against the simulator's truth): every step exits 0, the map has lane lines that
# evaluate finds near the true ones, and map.osm has lanelets. The full-size run and its figures:
# scripts/bench/bench_opendrive.sh, docs/performance-opendrive.md.
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
SRC="${MAPFUSE_SOURCE_DIR:?}"
XODR="${MAPFUSE_SHARED:-$SRC/../shared}/data/maps/MONAEast.xodr"
fail() { echo "FAIL: $*" >&2; exit 1; }
if [[ ! -f "$XODR" ]]; then echo "skipped: $XODR absent"; exit 77; fi
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

"$BIN/simulate" -q --map "$XODR" --traversals 4 --route-length 500 -o "$TMP/sim" > /dev/null \
  || fail "simulate"
make -s -j2 -f "$SRC/scripts/crowd.mk" BIN="$BIN" LSM_DIR="$TMP/sim/lsm" WORK="$TMP/work" \
  TRUTH="$TMP/sim/truth/vector_map.json" TRUTH_TRAJ="$TMP/sim/truth" > /dev/null \
  || fail "crowd chain"
/usr/bin/python3 - "$TMP" "$XODR" <<'PY' || fail "figures"
import json, sys
tmp, xodr = sys.argv[1:]
sim = json.load(open(f"{tmp}/sim/simulate.summary.json"))
ws = sim["world_stats"]
assert ws["roads"] == 25 and ws["junctions"] == 4, ws
assert ws["lane_links_rejected"] == 0, ws
# Every traversal drove (routing through the junctions is checked by tests/sim/test_opendrive.cpp).
assert sim["drives"] == 4 and sim["km_driven"] > 0.4, sim["km_driven"]
agg = json.load(open(f"{tmp}/work/aggregate/aggregate.summary.json"))
assert agg["lanelet2"]["lanelets"] > 0, agg["lanelet2"]
ev = json.load(open(f"{tmp}/work/evaluate/evaluate.summary.json"))
lane = next(c for c in ev["maps"][-1]["classes"] if c["class"] == "lane_line")
print("lane line completeness", lane["completeness"], "relative precision m", lane.get("relative_precision_m"))
assert lane["completeness"] > 0.3, lane
PY
echo "opendrive_chain: ok"
