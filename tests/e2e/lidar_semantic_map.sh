#!/usr/bin/env bash
# End to end: lidar-semantic-map on 5 of the 30 sfnd frames (0..8, stride 2) with ENet and
# LiDAR-odometry poses; a second run must take the semantics from the ENet cache and produce
# byte-identical maps (determinism).
set -euo pipefail
source "$(cd "$(dirname "$0")" && pwd)/lib/kitti_sfnd.sh"  # BIN, DRIVE, MODEL, TMP or skip
OUT="$TMP"
run() {
  "$BIN/lidar-semantic-map" "$DRIVE" -o "$1" --segmenter enet --model "$MODEL" \
    --pose-source odometry --first-frame 0 --last-frame 8 --stride 2 --quiet
}
export DRIVE_DIR="$DRIVE" BIN_DIR="$BIN"
run "$OUT/a" > /dev/null
summary="$OUT/a/lidar-semantic-map.summary.json"
python3 - "$summary" "$OUT/a" <<'PY'
import json, sys, os
s = json.load(open(sys.argv[1])); out = sys.argv[2]
assert s["frames"] == 5, s["frames"]
assert s["semantics"]["from_network"] == 5, s["semantics"]
assert s["poses"]["source"] == "odometry" and s["poses"]["converged_scans"] >= 4, s["poses"]
# Error minimisation on by default, with the forests the build generated and their provenance
# (issue 24); a build without them (MAPFUSE_GENERATE_FORESTS=OFF) says it is off.
em = s["error_minimization"]
if os.path.exists(os.environ["BIN_DIR"] + "/../models/lidar-classifiers/provenance.json"):
    assert em["skipped"] is False and len(em["labels"]) > 0, em
    assert em["provenance"]["format"] == "mapfuse.lidar_forest_provenance", em
    assert em["provenance"]["training_seeds"] and em["provenance"]["files"], em
    # it filters, without erasing the map (the trained-on-simulation forests drop 7.5 % of the
    # projected points of sfnd frames 0-29)
    assert 0 < em["rejected_points"] < 0.5 * s["points_projected"], (em, s["points_projected"])
else:
    assert em["skipped"] is True and "no generated forests" in em["reason"], em
hist = s["label_histogram"]
for c in ("road", "vehicle"):
    assert hist[c] > 1000, (c, hist)
head = open(os.path.join(out, "map.ply"), "rb").read(400).decode("latin1")
assert ("element vertex %d\n" % s["voxels"]) in head, head
labels = sorted(os.listdir(os.path.join(out, "labels")))
assert labels == ["%010d.label" % i for i in (0, 2, 4, 6, 8)], labels
for i, name in zip((0, 2, 4, 6, 8), labels):
    scan = os.path.getsize(os.environ["DRIVE_DIR"] + "/velodyne_points/data/%010d.bin" % i)
    assert os.path.getsize(os.path.join(out, "labels", name)) * 4 == scan, name
assert s["bytes_per_voxel"] <= 64, s["bytes_per_voxel"]
print("first run ok:", s["voxels"], "voxels")
PY
# Second run: ENet outputs come from the cache in <out>/semantics_02.
mkdir -p "$OUT/b" && cp -r "$OUT/a/semantics_02" "$OUT/b/"
run "$OUT/b" > /dev/null
python3 -c "
import json,sys; s=json.load(open('$OUT/b/lidar-semantic-map.summary.json'))
assert s['semantics']['from_cache'] == 5 and s['semantics']['from_network'] == 0, s['semantics']"
cmp "$OUT/a/map.ply" "$OUT/b/map.ply"
cmp "$OUT/a/map.pcd" "$OUT/b/map.pcd"
# Bad input: a missing drive is an I/O error (exit 4), a bad option a usage error (exit 2).
set +e
"$BIN/lidar-semantic-map" "$OUT/nope" -o "$OUT/c" 2>/dev/null; rc=$?
[[ $rc -eq 4 ]] || { echo "expected exit 4, got $rc"; exit 1; }
"$BIN/lidar-semantic-map" "$DRIVE" -o "$OUT/c" --stride 0 2>/dev/null; rc=$?
[[ $rc -eq 2 ]] || { echo "expected exit 2, got $rc"; exit 1; }
echo "lidar_semantic_map e2e ok"
