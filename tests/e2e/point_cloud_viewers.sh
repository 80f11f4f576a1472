#!/usr/bin/env bash
# Point clouds as the viewers read them (issue 35): lidar-semantic-map's map.pcd through PCL's
# own converter (pcl_pcd2ply, Debian pcl-tools) keeps every point's colour, label, confidence
# and SemanticKITTI id, point for point equal to map.ply; where CloudCompare is installed
# (Debian cloudcompare, not in install-deps: 41 MB of Qt GUI), its headless load of map.ply
# shows label, confidence and semantic_kitti as scalar fields with the same values; where Open3D
# is installed, its tensor reader keeps every field of both files.
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
fail() { echo "FAIL: $*"; exit 1; }
command -v pcl_pcd2ply >/dev/null || fail "pcl_pcd2ply missing (pcl-tools, scripts/install-deps.sh)"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
drive=$("$BIN/simulate-lidar" -o "$TMP/sim" --seed 3 --frames 3 --azimuth-steps 500 --quiet)
"$BIN/lidar-semantic-map" "$drive" -o "$TMP/map" --pose-source odometry --quiet \
  >/dev/null 2>&1
pcl_pcd2ply -format 0 "$TMP/map/map.pcd" "$TMP/pcl.ply" > "$TMP/pcl.log" 2>&1 ||
  { cat "$TMP/pcl.log"; fail "pcl_pcd2ply"; }

# Reads map.ply (binary, ours) and an ASCII PLY or CloudCompare ASC export; compares them.
cat > "$TMP/compare.py" <<'PY'
import struct, sys
def ours(path):
    b = open(path, "rb").read(); i = b.index(b"end_header\n") + len("end_header\n")
    rec = struct.Struct("<3f3Bifi")
    return [rec.unpack_from(b, i + k * rec.size) for k in range((len(b) - i) // rec.size)]
def ascii_rows(path, kind):
    lines = open(path).read().splitlines()
    if kind == "ply":
        props = [l.split()[-1] for l in lines[:lines.index("end_header")]
                 if l.startswith("property") and "view_" not in l and "axis" not in l]
        n = int(next(l for l in lines if l.startswith("element vertex")).split()[-1])
        rows = [l.split() for l in lines[lines.index("end_header") + 1:][:n]]
    else:  # CloudCompare ASC with -ADD_HEADER: "//X Y Z R G B label confidence semantic_kitti"
        props = [p.lower() for p in lines[0].lstrip("/").split()]
        rows = [l.split() for l in lines[1:]]
    return props, rows
mine = ours(sys.argv[1]); props, rows = ascii_rows(sys.argv[2], sys.argv[3])
names = {"ply": ["x", "y", "z", "red", "green", "blue", "label", "confidence", "semantic_kitti"],
         "asc": ["x", "y", "z", "r", "g", "b", "label", "confidence", "semantic_kitti"]}[sys.argv[3]]
missing = [n for n in names if n not in props]
assert not missing, f"{sys.argv[2]}: fields {missing} dropped (has {props})"
assert len(rows) == len(mine), (len(rows), len(mine))
col = [props.index(n) for n in names]
colours = {}
for k, (p, q) in enumerate(zip(mine, rows)):
    v = [float(q[c]) for c in col]
    assert all(abs(a - b) <= 1e-4 for a, b in zip(p[:3], v[:3])), (k, p, v)   # xyz, printed
    assert tuple(p[3:7]) == tuple(int(x) for x in v[3:7]), (k, p, v)          # RGB and label
    assert abs(p[7] - v[7]) <= 1e-6 and p[8] == int(v[8]), (k, p, v)           # conf, KITTI id
    colours.setdefault(p[6], set()).add(tuple(p[3:6]))
assert len(colours) >= 3 and all(len(c) == 1 for c in colours.values()), colours
# vehicle (7): SemanticKITTI's car colour, BGR [245, 150, 100] in its semantic-kitti.yaml
assert colours.get(7) == {(100, 150, 245)}, colours.get(7)
print(f"{sys.argv[3]}: {len(rows)} points, labels {sorted(colours)} with their colours")
PY
python3 "$TMP/compare.py" "$TMP/map/map.ply" "$TMP/pcl.ply" ply || fail "PCL's PLY differs from map.ply"

if command -v CloudCompare >/dev/null; then
  (cd "$TMP" && timeout 300 env QT_QPA_PLATFORM=offscreen CloudCompare -SILENT -AUTO_SAVE OFF \
     -O map/map.ply -C_EXPORT_FMT ASC -PREC 9 -ADD_HEADER -SAVE_CLOUDS FILE cc.asc) \
    > "$TMP/cc.log" 2>&1 || { cat "$TMP/cc.log"; fail "CloudCompare could not load map.ply"; }
  python3 "$TMP/compare.py" "$TMP/map/map.ply" "$TMP/cc.asc" asc || fail "CloudCompare dropped a field"
else
  echo "point_cloud_viewers: CloudCompare not installed, its check skipped (apt-get install cloudcompare)"
fi
# Open3D's tensor reader (Debian python3-open3d, not in install-deps: 21 packages), where
# installed: every field of both files, with the values of map.ply.
if /usr/bin/python3 -c "import open3d" 2>/dev/null; then
  /usr/bin/python3 - "$TMP/map" <<'PY' 2>&1 | grep -v -i "warning" || fail "Open3D dropped a field"
import sys, numpy as np, open3d as o3d
ply = o3d.t.io.read_point_cloud(sys.argv[1] + "/map.ply").point
pcd = o3d.t.io.read_point_cloud(sys.argv[1] + "/map.pcd").point
for name in ("scalar_label", "scalar_confidence", "scalar_semantic_kitti", "colors"):
    assert name in ply, f"map.ply: Open3D has no {name}"
for name in ("label", "confidence", "semantic_kitti", "colors"):
    assert name in pcd, f"map.pcd: Open3D has no {name}"
for a, b in (("colors", "colors"), ("scalar_label", "label"), ("scalar_confidence", "confidence"),
             ("scalar_semantic_kitti", "semantic_kitti")):
    assert np.array_equal(ply[a].numpy().astype(np.float64), pcd[b].numpy().astype(np.float64)), a
print(f"open3d: {len(ply['positions'])} points, every field in both files")
PY
else
  echo "point_cloud_viewers: Open3D not installed, its check skipped (apt-get install python3-open3d)"
fi
echo "point_cloud_viewers: ok"
