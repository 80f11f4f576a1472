#!/usr/bin/env bash
# The README's main job on the embedded sample (samples/demo/):
#   crowd:  simulate raw drives -> lsm-build -> georef -> align -> aggregate -> evaluate
#           (the same rules as scripts/crowd.mk, which it runs)
#   LiDAR:  simulate-lidar -> lidar-semantic-map -> evaluate voxels
# Leaves every output in one folder (default out/demo) with a README saying what each file is,
# and prints a short result table. Usage: scripts/demo.sh [BIN_DIR] [OUT_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
out=${2:-$root/out/demo}
mkdir -p "$out"
out=$(cd "$out" && pwd)
jobs=$(nproc 2>/dev/null || echo 2)
start=$(date +%s)
say() { echo "demo: $*" >&2; }

# ---------------------------------------------------------------- crowdsourced vector map
say "1/2 crowdsourced vector map: simulate raw drives"
# Seed 2: the world and two routes that share about 60 % of their road (issue 35), so that align
# ties the drives of both routes into one map. The config's own seed (42) gives two routes with
# no marking in common, and the benchmarks that read the config keep it (docs/performance*.md).
if [ ! -f "$out/sim/simulate.summary.json" ]; then
  "$bin/simulate" -q --config "$root/samples/demo/crowd-frames.json" --seed 2 -o "$out/sim" \
    >/dev/null
fi
say "lsm-build -> georef -> align -> aggregate -> evaluate (make -f scripts/crowd.mk)"
make -s -j"$jobs" -f "$root/scripts/crowd.mk" BIN="$bin" FRAMES_DIR="$out/sim/frames" \
  WORK="$out/crowd" TRUTH="$out/sim/truth/vector_map.json" TRUTH_TRAJ="$out/sim/truth" >/dev/null
cp "$out/crowd/aggregate/map.geojson" "$out/crowd-map.geojson"
cp "$out/crowd/aggregate/map.png" "$out/crowd-map.png"

# ---------------------------------------------------------------- LiDAR + camera voxel map
if [ -f "$root/samples/demo/lidar.sh" ]; then
  say "2/2 LiDAR + camera semantic voxel map"
  BIN="$bin" OUT="$out" bash "$root/samples/demo/lidar.sh"
fi

# ---------------------------------------------------------------- results
cat > "$out/README.md" <<'MD'
# mapfuse demo outputs

Made by `make demo` (scripts/demo.sh) from the embedded sample in samples/demo/.

| path | what |
|---|---|
| sim/ | simulated crowdsourced drives: `frames/<drive>/` raw camera/IMU/wheel/GPS data (docs/formats-frames.md), `truth/vector_map.json` (+ .geojson) the true map, `truth/<drive>.trajectory.json` true keyframe poses |
| crowd/lsm/ | one local semantic map per drive, built by `lsm-build` (odometry frame) |
| crowd/origin.txt | the batch's shared ENU origin (first GPS fix) |
| crowd/georef/ | LSMs georeferenced by `georef` (ENU of the shared origin) |
| crowd/align/ | LSMs aligned by `align` (SGICP + PCM + pose graph + GBA), `align.summary.json` |
| crowd/aggregate/ | the vector map: `map.cbor` (compact native), `map.json`, `map.geojson` (WGS84, opens in QGIS), `map.osm` (Lanelet2-style), `map.png` (top-down picture), `aggregate.summary.json` (size in KB/km) |
| crowd/evaluate/ | `evaluate.md` (paper-style table), `evaluate.summary.json`, `error_per_class.png` |
| crowd-map.geojson, crowd-map.png | copies of the map for a quick look |
| lidar/sim/ | a synthetic KITTI raw drive with ground truth (`simulate-lidar`: velodyne, oxts, image_02, semantics_02 network-like probabilities, labels/ true SemanticKITTI labels); docs/lidar-ground-truth.md |
| lidar/map/ | `lidar-semantic-map` output: `map.ply` (x, y, z, RGB, scalar fields label, confidence, semantic_kitti; CloudCompare), `map.pcd` (PCL: rgb, label, confidence, semantic_kitti), `labels/<frame>.label` (SemanticKITTI), `topdown.png`, `poses.txt` |
| lidar/evaluate/ | `voxels.md` / `voxels.json`: per-class accuracy and IoU (paper Table 1 layout) |
| lidar-map.png | copy of the top-down picture of the voxel map |

Every stage folder also holds `<stage>.config.json` (parameters used) and `<stage>.summary.json`.
MD

echo
echo "== crowdsourced vector map (evaluate vs ground truth) =="
cat "$out/crowd/evaluate/evaluate.md"
if [ -f "$out/lidar/evaluate/voxels.md" ]; then
  echo
  echo "== LiDAR semantic voxel map (IoU vs ground truth) =="
  cat "$out/lidar/evaluate/voxels.md"
fi
echo
echo "demo: outputs in $out (see $out/README.md), $(( $(date +%s) - start )) s"
