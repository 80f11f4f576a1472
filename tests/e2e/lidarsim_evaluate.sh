#!/usr/bin/env bash
# simulate-lidar -> evaluate voxels: a tiny synthetic drive, its own truth labels as predictions
# (mean IoU 1) and a corrupted copy (road called sidewalk in every scan: road IoU 0); then, when
# lidar-semantic-map is built, the full chain on the same drive (voxel map vs truth voxels).
set -euo pipefail
bin="$MAPFUSE_BIN_DIR"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
drive=$("$bin/simulate-lidar" -o "$tmp/sim" --seed 3 --frames 3 --azimuth-steps 500 --quiet)
[ -d "$drive/velodyne_points/data" ] && [ -f "$drive/labels/0000000002.label" ]
[ -f "$drive/semantics_02/0000000000.prob" ] && [ -f "$drive/oxts/data/0000000000.txt" ]

"$bin/evaluate" voxels --drive "$drive" --predicted-labels "$drive/labels" -o "$tmp/self" --quiet > "$tmp/self.md"
grep -q "| IoU (%) | 100.0 | 100.0 | 100.0 |" "$tmp/self.md"
python3 - "$tmp/self/voxels.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert abs(d["scores"]["mean_iou"] - 1.0) < 1e-12, d["scores"]["mean_iou"]
PY

# Road points (ids 40 and 60) relabelled sidewalk (48) in every scan: road IoU 0.
mkdir -p "$tmp/bad"
python3 - "$drive/labels" "$tmp/bad" <<'PY'
import array, os, sys
src, dst = sys.argv[1], sys.argv[2]
for name in sorted(os.listdir(src)):
    a = array.array("I"); a.frombytes(open(os.path.join(src, name), "rb").read())
    b = array.array("I", [((w & 0xFFFF0000) | 48) if (w & 0xFFFF) in (40, 60) else w for w in a])
    open(os.path.join(dst, name), "wb").write(b.tobytes())
PY
"$bin/evaluate" voxels --drive "$drive" --predicted-labels "$tmp/bad" -o "$tmp/bad_out" --quiet > "$tmp/bad.md"
grep -q "| IoU (%) | 0.0 |" "$tmp/bad.md"

# Without OXTS: LiDAR odometry, then evaluate voxels with the map's own poses.txt (issue 24).
# The same map scored with the truth poses (OXTS) and with its poses file agrees.
if [ -x "$bin/lidar-semantic-map" ]; then
  nox="$tmp/nox/2011_09_26/2011_09_26_drive_0001_sync"
  mkdir -p "$nox"
  ln -s "$drive/../"calib_*.txt "$tmp/nox/2011_09_26/"
  for part in velodyne_points image_02 labels semantics_02; do ln -s "$drive/$part" "$nox/$part"; done
  "$bin/lidar-semantic-map" "$nox" -o "$tmp/map" --quiet > /dev/null
  python3 -c "import json,sys; s=json.load(open(sys.argv[1])); assert s['poses']['source'] == 'odometry', s['poses']" \
    "$tmp/map/lidar-semantic-map.summary.json"
  set +e
  "$bin/evaluate" voxels --drive "$nox" --map "$tmp/map/map.ply" -o "$tmp/nopose" --quiet 2> "$tmp/err.txt"
  rc=$?
  set -e
  [ $rc -eq 3 ] || { echo "evaluate without poses: expected exit 3, got $rc"; exit 1; }
  grep -q "poses-file" "$tmp/err.txt"
  "$bin/evaluate" voxels --drive "$nox" --map "$tmp/map/map.ply" --poses-file "$tmp/map/poses.txt" \
    -o "$tmp/pf" --quiet > /dev/null
  python3 - "$tmp/pf/voxels.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
c = d["counts"]
# The truth voxels are built in the map's own frame: nearly every map voxel meets one.
assert c["unmatched_map_voxels"] <= 0.1 * c["map_voxels"], c
assert d["scores"]["mean_iou"] > 0.3, d["scores"]
print("evaluate voxels with poses.txt: mean IoU %.3f, %d of %d map voxels unmatched"
      % (d["scores"]["mean_iou"], c["unmatched_map_voxels"], c["map_voxels"]))
PY
fi
echo "lidarsim_evaluate: ok"
