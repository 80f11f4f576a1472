#!/usr/bin/env bash
# e2e (issue 22): `localize` on simulated, georeferenced drives against the true map: exit 0 with
# the trajectory, error table, plot and summary; a map with nothing near the drives is lost:
# exit 3 naming the rule, previous outputs byte-identical; bad inputs named (file and field).
set -euo pipefail
source "$(dirname "$0")/lib/scratch.sh"  # BIN; TMP, the working folder
fail() { echo "localize e2e: $*" >&2; exit 1; }

"$BIN/simulate" -q --traversals 2 --route-length 500 -o sim >/dev/null
"$BIN/georef" -q -o geo sim/lsm/*.cbor >/dev/null
"$BIN/localize" -q --map sim/truth/vector_map.json --truth-trajectories sim/truth -o loc \
  geo/*.cbor >/dev/null
for f in sim/lsm/*.cbor; do
  d=$(basename "$f" .lsm.cbor)
  for out in "$d.trajectory.json" "$d.errors.csv" "$d.errors.png"; do
    [[ -s loc/$out ]] || fail "missing loc/$out"
  done
done
python3 - loc/localize.summary.json <<'PY' || fail "summary check failed"
import json, sys
s = json.load(open(sys.argv[1]))
loc, prior = s["localized"], s["prior"]
# loose sanity bounds (the accuracy targets are the unit test's and the bench's)
assert s["lost_share"] <= 0.05, s["lost_share"]
assert loc["mean_abs_lateral_m"] < 0.2 and loc["mean_abs_longitudinal_m"] < 0.5, loc
assert loc["mean_abs_heading_deg"] < 0.5, loc
assert loc["mean_abs_lateral_m"] < prior["mean_abs_lateral_m"], (loc, prior)
assert s["localisations_per_second_per_core"] > 0
PY
sum_before=$(cd loc && sha256sum * | sha256sum)

# the map 1 km east: nothing near the drives, every keyframe lost -> exit 3, outputs untouched
python3 - sim/truth/vector_map.json far.json <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
for inst in m["instances"]:
    for key in ("points",):
        for p in inst.get(key, []):
            p[0] += 1000.0
    inst.pop("bezier", None)
json.dump(m, open(sys.argv[2], "w"))
PY
rc=0; "$BIN/localize" -q --map far.json -o loc geo/*.cbor >/dev/null 2>err.txt || rc=$?
[[ $rc == 3 ]] || { cat err.txt; fail "off-map run gave exit $rc, not 3"; }
grep -q "lost" err.txt && grep -q "max_lost_share" err.txt || { cat err.txt; fail "no lost message"; }
[[ $(cd loc && sha256sum * | sha256sum) == "$sum_before" ]] || fail "outputs changed by a failed run"

# bad inputs, named: an LSM not georeferenced (file, frame); a malformed map (file, field)
rc=0; "$BIN/localize" -q --map sim/truth/vector_map.json -o bad sim/lsm/*.cbor >/dev/null 2>err.txt || rc=$?
[[ $rc == 3 ]] && grep -q "sim/lsm/" err.txt && grep -q "enu" err.txt \
  || { cat err.txt; fail "odom LSM gave exit $rc"; }
python3 - sim/truth/vector_map.json broken.json <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["instances"][0]["points"] = "oops"
json.dump(m, open(sys.argv[2], "w"))
PY
rc=0; "$BIN/localize" -q --map broken.json -o bad geo/*.cbor >/dev/null 2>err.txt || rc=$?
[[ $rc == 3 ]] && grep -q "broken.json" err.txt && grep -q "points" err.txt \
  || { cat err.txt; fail "malformed map gave exit $rc"; }
# a truth folder without the drive's trajectory: I/O error naming it
mkdir empty_truth
rc=0; "$BIN/localize" -q --map sim/truth/vector_map.json --truth-trajectories empty_truth -o bad \
  geo/*.cbor >/dev/null 2>err.txt || rc=$?
[[ $rc == 4 ]] && grep -q "empty_truth" err.txt || { cat err.txt; fail "missing truth gave exit $rc"; }
# one drive twice: refused (exit 2), both outputs would have one name
rc=0; "$BIN/localize" -q --map sim/truth/vector_map.json -o bad geo/*.cbor geo/*.cbor >/dev/null 2>err.txt || rc=$?
[[ $rc == 2 ]] || { cat err.txt; fail "duplicate drives gave exit $rc"; }
[[ ! -e bad/localize.summary.json ]] || fail "a failed run left a summary"
echo "localize: ok"
