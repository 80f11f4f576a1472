#!/usr/bin/env bash
# e2e (issue 34): a map update through the batch tools. A map from 8 traversals of one route
# (scripts/crowd.mk), the same world changed (2 changes of each kind), 4 new traversals; then
# `make -f crowd.mk UPDATE_MAP=... LSM_DIR=new` (georef in the map's frame, update). Checked:
# the updated map keeps every unchanged element's JSON object byte for byte, drops the removed
# ones, versions the changed ones, appends the added ones; the report is valid JSON / GeoJSON;
# change-detection F1 against the simulator's change truth at least kMinF1.
set -euo pipefail
SRC="${MAPFUSE_SOURCE_DIR:?}"
source "$SRC/tests/e2e/lib/scratch.sh"
fail() { echo "FAIL: $*" >&2; exit 1; }
PY=/usr/bin/python3
K_MIN_F1=0.6  # F1 over all changes from 4 new traversals (measured 0.75, 2026-11-29)

SIM=(--routes 1 --route-length 800 --seed 5)
"$BIN/simulate" -q "${SIM[@]}" --traversals 8 -o before >/dev/null
"$BIN/simulate" -q "${SIM[@]}" --traversals 12 --change-removed 2 --change-added 2 \
  --change-moved 2 --change-restriped 2 --change-retyped 2 --change-seed 3 -o after >/dev/null
# the map in the truth's frame (simulate's origin), so that its ids can be matched to the truth's
make -s -j2 -f "$SRC/scripts/crowd.mk" BIN="$BIN" LSM_DIR=before/lsm WORK=crowd ORIGIN=49,8.4,110 \
  map >/dev/null
mkdir new
for i in 008 009 010 011; do cp after/lsm/*_trav$i.lsm.cbor new/; done
make -s -j2 -f "$SRC/scripts/crowd.mk" BIN="$BIN" UPDATE_MAP=crowd/aggregate/map.json \
  LSM_DIR=new WORK=upd >/dev/null
U=upd/update
for f in map.json map.cbor map.geojson map.osm changes.json changes.geojson update.summary.json; do
  [ -s "$U/$f" ] || fail "$U/$f missing"
done
[ "$(ls "$U"/registered/*.lsm.cbor | wc -l)" = 4 ] || fail "registered drives missing"
"$PY" - crowd/aggregate/map.json "$U" <<'PYEOF'
import json, sys
before = {i["id"]: i for i in json.load(open(sys.argv[1]))["instances"]}
out = sys.argv[2]
after = {i["id"]: i for i in json.load(open(out + "/map.json"))["instances"]}
s = json.load(open(out + "/update.summary.json"))
u = s["updated_map"]
assert s["traversals"] == 4, s["traversals"]
removed, changed, added = set(u["removed_ids"]), set(u["changed_ids"]), set(u["added_ids"])
assert u["unchanged"] + len(removed) + len(changed) == len(before), u
for i, b in before.items():
    if i in removed:
        assert i not in after, "removed element %d still in the map" % i
    elif i in changed:
        assert after[i].get("version", 1) == b.get("version", 1) + 1, "element %d not versioned" % i
    else:
        assert json.dumps(after[i], sort_keys=True) == json.dumps(b, sort_keys=True), \
            "unchanged element %d differs" % i
for i in added:
    assert i in after and i not in before, "addition %d" % i
assert json.load(open(out + "/changes.geojson"))["type"] == "FeatureCollection"
print("updated map: %d unchanged, %d changed, %d removed, %d added" %
      (u["unchanged"], len(changed), len(removed), len(added)))
PYEOF
"$PY" "$SRC/scripts/changes-to-truth-ids.py" "$U/changes.json" crowd/aggregate/map.json \
  before/truth/vector_map.json ids.json 2>/dev/null
"$BIN/evaluate" changes -q --detected ids.json --truth after/truth/changes.json \
  --before before/truth/vector_map.json -o ev
"$PY" - ev/change-scores.json "$K_MIN_F1" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1]))
f1 = s["overall"]["f1"]
print("F1 over all changes: %.3f (bound %s)" % (f1, sys.argv[2]))
assert f1 >= float(sys.argv[2]), f1
PYEOF
echo "map_update: ok"
