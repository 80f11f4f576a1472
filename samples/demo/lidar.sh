#!/usr/bin/env bash
# LiDAR half of the demo (called by scripts/demo.sh with BIN and OUT set):
# a seeded synthetic KITTI raw drive with ground truth -> lidar-semantic-map (OXTS poses,
# precomputed network-like semantics) -> evaluate voxels (IoU, Jeong et al. 2018 eq. 10-11).
set -euo pipefail
: "${BIN:?}" "${OUT:?}"
lidar="$OUT/lidar"
if [ ! -f "$lidar/drive.txt" ]; then
  # seed 1: parked cars along the curb as well as moving ones, so the vehicle row is scored
  "$BIN/simulate-lidar" -q --seed 1 --frames 15 -o "$lidar/sim" > "$lidar.drive.tmp"
  mkdir -p "$lidar" && mv "$lidar.drive.tmp" "$lidar/drive.txt"
fi
drive=$(cat "$lidar/drive.txt")
if [ ! -f "$lidar/map/lidar-semantic-map.summary.json" ]; then
  "$BIN/lidar-semantic-map" -q "$drive" -o "$lidar/map" >/dev/null
fi
"$BIN/evaluate" voxels -q --drive "$drive" --map "$lidar/map/map.ply" -o "$lidar/evaluate" >/dev/null
cp "$lidar/map/topdown.png" "$OUT/lidar-map.png"
