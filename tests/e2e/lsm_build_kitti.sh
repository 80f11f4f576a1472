#!/usr/bin/env bash
# e2e: lsm-build on real KITTI images (2011_09_26 sfnd, frames 0-1) with the fallback
# perception (ENet road + BEV top-hat lanes) and a poses file; checks the LSM, the summary
# and the bird's-eye PNG. Skips (77) without ../shared data.
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
SHARED="${MAPFUSE_SHARED:?}"
DRIVE="$SHARED/data/kitti_raw/2011_09_26/2011_09_26_drive_sfnd_sync"
MODEL="$SHARED/models/enet-cityscapes/enet-model.net"
[[ -d "$DRIVE" && -f "$MODEL" ]] || { echo "SKIP: KITTI sfnd drive or ENet model absent"; exit 77; }
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
# Stand-in poses (camera 0, z forward): 0.5 m per frame. Real runs use the LiDAR pipeline's.
printf '1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 0.5\n' > "$TMP/poses.txt"
lsm="$("$BIN/lsm-build" "$DRIVE" -o "$TMP/out" --poses "$TMP/poses.txt" --kitti-last-frame 1 \
  --model "$MODEL" --min-observations 1 --quiet)"
[[ -f "$lsm" ]] || { echo "FAIL: no LSM"; exit 1; }
[[ -s "$TMP/out/2011_09_26_drive_sfnd_sync.bev.png" ]] || { echo "FAIL: no PNG"; exit 1; }
grep -q '"semantics": "segmenter"' "$TMP/out/lsm-build.summary.json" || { echo "FAIL: summary"; exit 1; }
python3 - "$lsm" "$TMP/out/lsm-build.summary.json" <<'PY'
import json, sys
lsm = json.load(open(sys.argv[1]))
summary = json.load(open(sys.argv[2]))
# Every lane piece of the 2 frames is counted once by style (solid, dashed or untyped).
st = summary["lane_styles"]
assert st["solid"] + st["dashed"] + st["untyped"] >= 1, st
assert st["dash_period_m"] >= 0, st
lanes = [e for e in lsm["elements"] if e["class"] == "lane_line"]
assert len(lsm["keyframes"]) == 2, lsm["keyframes"]
assert lanes, "no lane lines extracted from the KITTI frames"
# Lane points lie on the road ahead of the camera within the BEV band, near the ground.
for e in lanes:
    for x, y, z in e["points"]:
        assert -5 < x < 45 and abs(y) < 12 and abs(z) < 3.5, (x, y, z)
print("lanes:", len(lanes))
PY
# Wrong poses count -> exit 3.
set +e
"$BIN/lsm-build" "$DRIVE" -o "$TMP/bad" --poses "$TMP/poses.txt" --kitti-last-frame 2 \
  --model "$MODEL" --quiet > /dev/null 2>&1; rc=$?
set -e
[[ $rc -eq 3 ]] || { echo "FAIL: poses count mismatch gave exit $rc"; exit 1; }
echo OK
