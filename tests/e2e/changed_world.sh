#!/usr/bin/env bash
# e2e (issue 34): simulate one world twice, without and with true changes. The "after" truth
# keeps every unchanged element's id and bytes, lists exactly the requested changes in
# truth/changes.json (valid GeoJSON beside it, WGS84, GEOS-valid), and drives run over it;
# evaluate changes gives F1 = 1 on the truth itself and the exact figures of a detection with
# one false removal and one missed change; a malformed change file is exit 3 naming the field.
# Then the same on the Lanelet2 Karlsruhe map (skipped when ../shared is absent).
set -euo pipefail
SRC="${MAPFUSE_SOURCE_DIR:?}"
source "$SRC/tests/e2e/lib/scratch.sh"
fail() { echo "FAIL: $*" >&2; exit 1; }
PY=/usr/bin/python3
N=4  # changes of each kind

# compare BEFORE_DIR AFTER_DIR N: the truths differ by exactly the listed changes.
compare() {
  "$PY" - "$1" "$2" "$3" <<'PYEOF'
import json, sys
from collections import Counter
before_dir, after_dir, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
raw = lambda d: {json.dumps(i, sort_keys=True): i for i in
                 json.load(open(d + "/truth/vector_map.json"))["instances"]}
before = {i["id"]: i for i in raw(before_dir).values()}
after = {i["id"]: i for i in raw(after_dir).values()}
doc = json.load(open(after_dir + "/truth/changes.json"))
assert doc["format"] == "mapfuse.map_changes" and doc["version"] == 1, doc["format"]
changes = doc["changes"]
kinds = Counter(c["kind"] for c in changes)
expected = {k: n for k in ("removed", "added", "moved", "restriped", "retyped")}
assert dict(kinds) == expected, kinds
named = {c["before_id"] for c in changes if "before_id" in c}
for i, inst in before.items():
    if i in named:
        continue
    assert after.get(i) == inst, "unchanged element %d differs" % i
for c in changes:
    if c["kind"] == "removed":
        assert c["before_id"] not in after
    else:
        a = after[c["after_id"]]
        assert a["points"] == c["after"]["points"], c
    if c["kind"] == "added":
        assert c["after_id"] not in before
summary = json.load(open(after_dir + "/simulate.summary.json"))
assert summary["changes"] == expected, summary["changes"]
print("unchanged %d of %d, changes %d" % (len(before) - len(named), len(before), len(changes)))
PYEOF
}

common=(-q --traversals 2 --route-length 300)
changes=(--change-removed $N --change-added $N --change-moved $N --change-restriped $N
         --change-retyped $N --change-seed 3)
"$BIN/simulate" "${common[@]}" -o before >/dev/null
"$BIN/simulate" "${common[@]}" "${changes[@]}" -o after >/dev/null
test ! -e before/truth/changes.json || fail "a run without changes wrote changes.json"
test "$(ls after/lsm | wc -l)" -eq 2 || fail "the drives over the changed world"
compare before after $N || fail "procedural truths"
"$PY" "$SRC/scripts/check-geojson.py" after/truth/changes.geojson || fail "changes.geojson"

# evaluate changes: the truth itself, then one false removal and one missed change.
ev() { "$BIN/evaluate" changes -q --truth after/truth/changes.json \
         --before before/truth/vector_map.json "$@"; }
ev --detected after/truth/changes.json -o ev_self >/dev/null
"$PY" - <<'PYEOF' || fail "F1 of the truth itself"
import json
s = json.load(open("ev_self/evaluate-changes.summary.json"))
assert s["f1"] == 1.0 and s["precision"] == 1.0 and s["recall"] == 1.0, s
assert all(v == 1.0 for v in s["f1_by_kind"].values()), s["f1_by_kind"]
assert s["false_removals"]["count"] == 0
PYEOF
"$PY" - <<'PYEOF'
import json
doc = json.load(open("after/truth/changes.json"))
before = json.load(open("before/truth/vector_map.json"))["instances"]
named = {c["before_id"] for c in doc["changes"] if "before_id" in c}
moved = [c for c in doc["changes"] if c["kind"] == "moved"]
doc["changes"].remove(moved[0])                                   # one missed change
victim = next(i for i in before if i["id"] not in named and i["class"] == "pole")
state = {"points": victim["points"], "height": victim["height"]}
doc["changes"].append({"kind": "removed", "class": "pole", "before_id": victim["id"],
                       "before": state, "confidence": 0.6,
                       "supporting_traversals": ["veh00_trav000"]})  # one false removal
json.dump(doc, open("detected.json", "w"))
json.dump({"unchanged": len(before) - len(named)}, open("unchanged.json", "w"))
PYEOF
ev --detected detected.json -o ev_one >/dev/null
"$PY" - "$N" <<'PYEOF' || fail "figures of one false removal and one missed change"
import json, sys
n = 5 * int(sys.argv[1])
s = json.load(open("ev_one/evaluate-changes.summary.json"))
unchanged = json.load(open("unchanged.json"))["unchanged"]
d = json.load(open("ev_one/change-scores.json"))
assert d["overall"]["tp"] == n - 1 and d["overall"]["fp"] == 1 and d["overall"]["fn"] == 1, d
for key in ("precision", "recall", "f1"):
    assert abs(s[key] - (n - 1) / n) < 1e-12, (key, s[key])
fr = s["false_removals"]
assert fr["count"] == 1 and fr["unchanged_elements"] == unchanged, fr
assert abs(fr["rate"] - 1 / unchanged) < 1e-12, fr
assert d["by_kind"]["moved"]["fn"] == 1 and d["by_kind"]["removed"]["fp"] == 1
PYEOF
# A malformed change file: exit 3, the file and the field named.
"$PY" -c 'import json; d = json.load(open("detected.json")); d["changes"][2]["kind"] = "vanished"
json.dump(d, open("bad.json", "w"))'
rc=0; ev --detected bad.json -o ev_bad 2> bad.err >/dev/null || rc=$?
test "$rc" -eq 3 || fail "malformed change file: exit $rc"
grep -q "bad.json.*changes\[[0-9]*\]\.kind" bad.err || fail "error names file and field: $(cat bad.err)"

# A map world: the Lanelet2 Karlsruhe map.
MAP="${MAPFUSE_SHARED:-$SRC/../shared}/data/maps/lanelet2_karlsruhe_mapping_example.osm"
if [ ! -f "$MAP" ]; then echo "SKIP: $MAP absent"; exit 77; fi
"$BIN/simulate" "${common[@]}" --level truth --map "$MAP" -o kbefore >/dev/null
"$BIN/simulate" "${common[@]}" --level truth --map "$MAP" "${changes[@]}" -o kafter >/dev/null
compare kbefore kafter $N || fail "Karlsruhe truths"
"$PY" "$SRC/scripts/check-geojson.py" kafter/truth/changes.geojson || fail "Karlsruhe changes.geojson"
echo "changed_world: ok"
