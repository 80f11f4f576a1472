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

if [ -x "$bin/lidar-semantic-map" ]; then
  "$bin/lidar-semantic-map" --help > /dev/null
fi
echo "lidarsim_evaluate: ok"
