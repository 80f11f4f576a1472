#!/usr/bin/env bash
# Ablation of the LiDAR pipeline on a held-out synthetic drive (docs/lidar-ground-truth.md):
# single-frame CNN projection, + Bayesian fusion, + error minimisation, + refinement, each scored
# with `evaluate voxels` (per-scan labels and voxel map), plus trace-removal shares. Prints the
# tables and writes docs/performance-lidar-ablation.md.
# usage: scripts/bench/bench_lidarsim_ablation.sh [BIN_DIR=build/bin] [WORK=/tmp/lidarsim-ablation]
# env: SEED=900 FRAMES=30 TRAIN_SEEDS="101 102 103 104" TRAIN_FRAMES=40 (train-classifiers.sh defaults)
set -euo pipefail
bin=$(cd "${1:-build/bin}" && pwd)
work=${2:-/tmp/lidarsim-ablation}
root=$(cd "$(dirname "$0")/../.." && pwd)
seed=${SEED:-900}
frames=${FRAMES:-30}
mkdir -p "$work" && cd "$work"
drive=$("$bin/simulate-lidar" -o sim --seed "$seed" --drive "$seed" --frames "$frames" --quiet)
SEEDS=${TRAIN_SEEDS:-"101 102 103 104"} FRAMES=${TRAIN_FRAMES:-40} WORK="$work/train" \
  bash "$root/scripts/train-classifiers.sh" "$bin" "$work/forests" > /dev/null
# Single frame: each scan mapped alone (its own CNN probabilities only), per-scan labels.
mkdir -p single_labels
for ((k = 0; k < frames; ++k)); do
  "$bin/lidar-semantic-map" "$drive" -o "single/$k" --first-frame $k --last-frame $k --refine 0 --quiet > /dev/null
  cp "single/$k/labels/"*.label single_labels/
done
"$bin/evaluate" voxels --drive "$drive" --predicted-labels single_labels -o eval_scan_single --title "single frame" --quiet > /dev/null
"$bin/lidar-semantic-map" "$drive" -o fused --refine 0 --quiet > /dev/null
"$bin/lidar-semantic-map" "$drive" -o errmin --refine 0 --classifier-dir forests --quiet > /dev/null
"$bin/lidar-semantic-map" "$drive" -o full --classifier-dir forests --quiet > /dev/null
for r in fused errmin full; do
  "$bin/evaluate" voxels --drive "$drive" --map $r/map.ply -o eval_map_$r --title $r --quiet > /dev/null
  "$bin/evaluate" voxels --drive "$drive" --predicted-labels $r/labels -o eval_scan_$r --title $r --quiet > /dev/null
done
tables="$PWD/tables.md"
python3 - <<'PY' | tee "$tables"
import json
classes = ["road", "sidewalk", "building", "fence", "pole", "vegetation", "vehicle"]
def row(name, path):
    d = json.load(open(path))["scores"]
    f = lambda x: "-" if x is None else f"{100 * x:.1f}"
    return "| " + name + " | " + " | ".join(f(d["classes"][c]["iou"]) for c in classes) + f" | {f(d['mean_iou'])} |"
print("Per-scan labels, IoU (%):\n")
print("| run | " + " | ".join(classes) + " | mean |\n|---|" + "---:|" * 8)
for n, p in [("single frame", "eval_scan_single"), ("+ Bayesian fusion", "eval_scan_fused"),
             ("+ error minimisation", "eval_scan_errmin"), ("+ refinement", "eval_scan_full")]:
    print(row(n, p + "/voxels.json"))
print("\nVoxel map vs truth voxels, IoU (%):\n")
print("| run | " + " | ".join(classes) + " | mean |\n|---|" + "---:|" * 8)
for n, p in [("Bayesian fusion", "eval_map_fused"), ("+ error minimisation", "eval_map_errmin"),
             ("+ refinement", "eval_map_full")]:
    print(row(n, p + "/voxels.json"))
print("\nTrace removal (voxel map):\n\n| run | moving-car voxels removed | parked-car voxels kept |\n|---|---:|---:|")
for n, p in [("Bayesian fusion", "eval_map_fused"), ("+ error minimisation", "eval_map_errmin"), ("+ refinement", "eval_map_full")]:
    t = json.load(open(p + "/voxels.json"))["trace_removal"]
    print(f"| {n} | {100 * t['moving_removed_share']:.1f} % of {t['moving_truth_voxels']} | {100 * t['parked_kept_share']:.1f} % of {t['parked_truth_voxels']} |")
PY
{
  echo "# Performance: LiDAR pipeline ablation on a held-out simulated drive"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "- machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "- command: \`scripts/bench/bench_lidarsim_ablation.sh BIN_DIR WORK\`: held-out seed $seed, $frames"
  echo "  frames; forests from scripts/train-classifiers.sh on seeds ${TRAIN_SEEDS:-101 102 103 104}"
  echo "  (${TRAIN_FRAMES:-40} frames each); runs and scoring as in docs/lidar-ground-truth.md."
  echo
  cat "$tables"
} > "$root/docs/performance-lidar-ablation.md"
