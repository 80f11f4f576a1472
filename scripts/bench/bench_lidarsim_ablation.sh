#!/usr/bin/env bash
# Ablation of the LiDAR pipeline on a held-out synthetic drive (docs/lidar-ground-truth.md):
# single-frame CNN projection, + Bayesian fusion, + error minimisation, + refinement, each scored
# with `evaluate voxels` (per-scan labels and voxel map), plus trace-removal shares. Prints the
# tables and writes docs/performance-lidar-ablation.md.
# usage: scripts/bench/bench_lidarsim_ablation.sh [BIN_DIR=build/bin] [WORK=/tmp/lidarsim-ablation]
# env: SEED=900 FRAMES=30 TRAIN_SEEDS="101 102 103 104" VALIDATION_SEEDS="105 106 107"
#      TRAIN_FRAMES=40 (train-classifiers.sh defaults, i.e. the forests the build generates);
#      FORESTS=<folder> uses those forests instead of training (e.g. build/models/lidar-classifiers)
set -euo pipefail
bin=$(cd "${1:-build/bin}" && pwd)
work=${2:-/tmp/lidarsim-ablation}
root=$(cd "$(dirname "$0")/../.." && pwd)
seed=${SEED:-900}
frames=${FRAMES:-30}
mkdir -p "$work" && cd "$work"
drive=$("$bin/simulate-lidar" -o sim --seed "$seed" --drive "$seed" --frames "$frames" --quiet)
rm -rf "$work/train" "$work/forests"
if [[ -n "${FORESTS:-}" ]]; then
  cp -r "$FORESTS" "$work/forests"
else
  SEEDS=${TRAIN_SEEDS:-"101 102 103 104"} VALIDATION_SEEDS=${VALIDATION_SEEDS:-"105 106 107"} \
    FRAMES=${TRAIN_FRAMES:-40} WORK="$work/train" \
    bash "$root/scripts/train-classifiers.sh" "$bin" "$work/forests" > /dev/null
fi
# Single frame: each scan mapped alone (its own CNN probabilities only), per-scan labels.
mkdir -p single_labels
for ((k = 0; k < frames; ++k)); do
  "$bin/lidar-semantic-map" "$drive" -o "single/$k" --first-frame $k --last-frame $k --refine 0 --classifier-dir none --quiet > /dev/null
  cp "single/$k/labels/"*.label single_labels/
done
"$bin/evaluate" voxels --drive "$drive" --predicted-labels single_labels -o eval_scan_single --title "single frame" --quiet > /dev/null
"$bin/lidar-semantic-map" "$drive" -o fused --refine 0 --classifier-dir none --quiet > /dev/null
"$bin/lidar-semantic-map" "$drive" -o errmin --refine 0 --classifier-dir forests --quiet > /dev/null
"$bin/lidar-semantic-map" "$drive" -o full --classifier-dir forests --quiet > /dev/null
"$bin/lidar-semantic-map" "$drive" -o refined --classifier-dir none --quiet > /dev/null
for r in fused errmin full refined; do
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
             ("+ error minimisation", "eval_scan_errmin"), ("+ refinement", "eval_scan_full"),
             ("Bayesian fusion + refinement, no error minimisation", "eval_scan_refined")]:
    print(row(n, p + "/voxels.json"))
print("\nVoxel map vs truth voxels, IoU (%):\n")
print("| run | " + " | ".join(classes) + " | mean |\n|---|" + "---:|" * 8)
for n, p in [("Bayesian fusion", "eval_map_fused"), ("+ error minimisation", "eval_map_errmin"),
             ("+ refinement", "eval_map_full"),
             ("Bayesian fusion + refinement, no error minimisation", "eval_map_refined")]:
    print(row(n, p + "/voxels.json"))
print("\nTrace removal (voxel map):\n\n| run | moving-car voxels removed | parked-car voxels kept |\n|---|---:|---:|")
for n, p in [("Bayesian fusion", "eval_map_fused"), ("+ error minimisation", "eval_map_errmin"), ("+ refinement", "eval_map_full"),
             ("Bayesian fusion + refinement, no error minimisation", "eval_map_refined")]:
    t = json.load(open(p + "/voxels.json"))["trace_removal"]
    print(f"| {n} | {100 * t['moving_removed_share']:.1f} % of {t['moving_truth_voxels']} | {100 * t['parked_kept_share']:.1f} % of {t['parked_truth_voxels']} |")
PY
{
  echo "# Performance: LiDAR pipeline ablation on a held-out simulated drive"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "- machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "- command: \`scripts/bench/bench_lidarsim_ablation.sh BIN_DIR WORK\`: held-out seed $seed, $frames"
  echo "  frames; forests from scripts/train-classifiers.sh (the ones the build generates): training"
  echo "  seeds ${TRAIN_SEEDS:-101 102 103 104}, validation seeds ${VALIDATION_SEEDS:-105 106 107}"
  echo "  (${TRAIN_FRAMES:-40} frames each), thresholds $(tr -d ' \n' < forests/thresholds.json | sed 's/.*"labels"://;s/"min_correct_votes"://g;s/[{}]//g;s/"//g;s/,/, /g');"
  echo "  runs and scoring as in docs/lidar-ground-truth.md."
  echo
  cat "$tables"
  echo
  echo "Error minimisation is judged against the run without it: per scan \"+ Bayesian fusion\" ->"
  echo "\"+ error minimisation\", in the map the same and \"no error minimisation\" -> \"+ refinement\"."
  echo "Before issue 24 (every forest at its majority vote, no validation drives; run of"
  echo "2026-11-23) fence fell from 5.6 to 0.0 per scan and from 21.7 to 0.2 in the map. The"
  echo "thresholds are now chosen on the validation drives by the worst-drive rule of docs/lidar.md"
  echo "(\"Error-minimisation forests\"); the held-out drive plays no part in it."
} > "$root/docs/performance-lidar-ablation.md"
