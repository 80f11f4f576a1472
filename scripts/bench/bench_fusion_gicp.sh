#!/usr/bin/env bash
# GICP vs PCL GICP on KITTI odometry scans; writes docs/performance-fusion.md.
# Usage: scripts/bench/bench_fusion_gicp.sh [BIN_DIR]   (built with -DMAPFUSE_WITH_PCL=ON, the default)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
bin="${1:-$root/build/bin}"
out="$root/docs/performance-fusion.md"
table="$("$bin/bench_gicp" --repeats 3 --frames 6)"
{
  echo "# Performance: fusion (GICP core)"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "- machine: $(nproc) cores, $(lscpu | grep 'Model name' | sed 's/Model name: *//')"
  echo "- load average at start: $(cut -d' ' -f1-3 /proc/loadavg) (machine shared by other builds)"
  echo "- command: scripts/bench/bench_fusion_gicp.sh $bin"
  echo "- setup: KITTI odometry sequence 00 scans 0-5, 0.25 m voxel centroids (same clouds for both),"
  echo "  max correspondence 1.0 m, k = 10 covariance neighbours (PCL default 20), 64 iterations max;"
  echo "  mapfuse time includes covariance estimation of both clouds and index build; median of 3."
  echo
  echo "$table"
} > "$out"
echo "wrote $out"
