#!/usr/bin/env bash
# e2e (issue 22): bench_map_bound measures a map's error across the road against an independent
# reference: the true map scores 0; the true map shifted by a known vector scores the RMS of that
# shift across each true lane line (computed here from the truth file, length-weighted); the GPS
# columns do not depend on the map; the oracle writes every georeferenced LSM back.
set -euo pipefail
source "$(dirname "$0")/lib/scratch.sh"  # BIN; TMP, the working folder
fail() { echo "map_bound e2e: $*" >&2; exit 1; }

"$BIN/simulate" -q --traversals 4 --route-length 600 -o sim >/dev/null
"$BIN/georef" -q -o geo sim/lsm/*.cbor >/dev/null
python3 - sim/truth/vector_map.json shifted.json <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
for inst in m["instances"]:
    inst["points"] = [[p[0] + 0.4, p[1], p[2]] for p in inst["points"]]
json.dump(m, open(sys.argv[2], "w"))
PY
"$BIN/bench_map_bound" --sim sim --map sim/truth/vector_map.json --stage georef=geo \
  sim/lsm/*.cbor > true.json || fail "bench_map_bound failed on the true map"
"$BIN/bench_map_bound" --sim sim --map shifted.json --debias-in geo --debias-out oracle \
  sim/lsm/*.cbor > shifted.json.out || fail "bench_map_bound failed on the shifted map"
python3 - true.json shifted.json.out sim/truth/vector_map.json <<'PY' || fail "figures wrong"
import json, math, sys
t, s = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
truth = json.load(open(sys.argv[3]))
# the true map: no error
assert t["lateral"]["map"]["rms_m"] < 1e-6 and t["map_all_matched"]["rms_m"] < 1e-6, t
assert t["matched"] > 0.99 * t["lane_line_samples"], t
assert 0 < t["without_gps_nearby"] < t["matched"], t  # the drives cover part of the world
# the shifted map: n . (0.4, 0) over the true lane lines, weighted by length
sq = length = 0.0
for inst in truth["instances"]:
    if inst["class"] != "lane_line":
        continue
    p = inst["points"]
    for a, b in zip(p, p[1:]):
        dx, dy = b[0] - a[0], b[1] - a[1]
        ell = math.hypot(dx, dy)
        if ell == 0:
            continue
        d = -dy * 0.4 / ell  # n . (0.4, 0), n = (-dy, dx) / ell
        sq += d * d * ell
        length += ell
ref = math.sqrt(sq / length)
got = s["map_all_matched"]["rms_m"]
TOLERANCE = 0.006  # m: sampling every 1 m, line ends near crossings (measured 0.0025)
assert abs(got - ref) < TOLERANCE, (got, ref)
print(f"map_bound e2e: shifted map {got:.4f} m, reference {ref:.4f} m")
# what the GPS says does not depend on the map under test
for col in ("bound", "global"):
    assert abs(t["lateral"][col]["rms_m"] - s["lateral"][col]["rms_m"]) < 0.02, col
assert 0 < t["lateral"]["bound"]["rms_m"] < 5, t["lateral"]["bound"]
assert t["lateral"]["georef"]["rms_m"] > 0 and "georef_lines" in t["lateral"]
rel = t["relative_lateral_rms_m_by_keyframe_separation"]["georef"]
assert set(rel) == {"1", "12", "24"} and 0 < rel["1"] < rel["24"], rel  # drift grows
assert t["drives"] == 4 and t["gps_inlier_fixes"] > 0
PY
[[ $(ls oracle | wc -l) -eq 4 ]] || fail "oracle: expected 4 LSMs, got $(ls oracle)"
"$BIN/bench_map_bound" --sim sim --map sim/truth/vector_map.json --stage bad \
  sim/lsm/*.cbor > /dev/null 2>&1 && fail "--stage without NAME=DIR accepted"
echo "map_bound e2e: ok"
