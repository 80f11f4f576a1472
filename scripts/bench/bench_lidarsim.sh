#!/usr/bin/env bash
# Benchmark of simulate-lidar: wall time per frame and the summary's stage timings
# (LiDAR ray casting, camera rendering + network-error model, writing), default parameters.
# usage: scripts/bench/bench_lidarsim.sh [BIN_DIR=build/bin] [FRAMES=10]
# Writes docs/performance-lidarsim.md.
set -euo pipefail
bin=${1:-build/bin}
frames=${2:-10}
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmd="$bin/simulate-lidar -o $tmp --frames $frames --quiet"
start=$(date +%s.%N)
drive=$($cmd)
end=$(date +%s.%N)
summary="$drive/simulate-lidar.summary.json"
read -r lidar camera write total mean_pts <<<"$(python3 -c "
import json; s = json.load(open('$summary')); t = s['timings_s']
print(t['lidar'], t['camera_and_network'], t['write'], t['total'], s['points_per_scan']['mean'])")"
per() { python3 -c "print(f'{$1 / $frames:.3f}')"; }
size=$(du -sh "$drive" | cut -f1)
{
  echo "# Performance: simulate-lidar"
  echo
  echo "Produced by \`scripts/bench/bench_lidarsim.sh\` on $(date -u +%Y-%m-%d)."
  echo
  echo "- machine: $(nproc) cores, $(lscpu | grep 'Model name' | sed 's/Model name: *//'), load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "- command: \`$bin/simulate-lidar -o <tmp> --frames $frames --quiet\` (all other parameters default: 64 x 2150 rays, 1242 x 375 camera)"
  echo "- mean points per scan: $mean_pts; drive size on disk: $size"
  echo
  echo "| step | total (s) | per frame (s) |"
  echo "|---|---:|---:|"
  echo "| LiDAR ray casting | $lidar | $(per "$lidar") |"
  echo "| camera labels + network-error model | $camera | $(per "$camera") |"
  echo "| writing (bin, label, png, prob, oxts) | $write | $(per "$write") |"
  echo "| stage total | $total | $(per "$total") |"
  echo "| process wall time | $(python3 -c "print(f'{$end - $start:.2f}')") | $(per "($end - $start)") |"
  echo
  echo "Timings are wall-clock on a shared machine (OpenMP over beams and image rows); compare runs"
  echo "made at similar load only."
} > "$root/docs/performance-lidarsim.md"
cat "$root/docs/performance-lidarsim.md"
