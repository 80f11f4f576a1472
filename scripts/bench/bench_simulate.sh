#!/usr/bin/env bash
# Benchmark: `simulate --level lsm`, 50 traversals over ~10 km of procedural road, one core.
# Writes docs/performance-simulate.md. Usage: scripts/bench/bench_simulate.sh [BIN_DIR]
set -euo pipefail
SRC="$(cd "$(dirname "$0")/../.." && pwd)"
BIN="${1:-$SRC/build/bin}"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
CMD=(env OMP_NUM_THREADS=1 "$BIN/simulate" --level lsm --traversals 50 --routes 10
     --route-length 2000 --world-grid-size 5 --world-block-length 300 -o "$OUT" -q)
START=$(date +%s.%N)
"${CMD[@]}" > "$OUT.summary.json"
END=$(date +%s.%N)
SECONDS_TAKEN=$(echo "$END - $START" | bc)
read -r ROAD_KM LINE_KM KM OBS <<<"$(python3 -c "import json;d=json.load(open('$OUT.summary.json'));print(round(d['world_stats']['road_km'],2),round(d['lane_line_km'],2),round(d['km_driven'],2),d['observations'])")"
SIZE=$(du -sh "$OUT/lsm" | cut -f1)
rm -f "$OUT.summary.json"
cat > "$SRC/docs/performance-simulate.md" <<MD
# Performance: simulate

| item | value |
|---|---|
| date | $(date -u +%Y-%m-%d) |
| machine | $(nproc) cores, $(lscpu | grep 'Model name' | sed 's/Model name: *//') |
| command | \`${CMD[*]:1}\` (OMP_NUM_THREADS=1) |
| world | procedural 5 x 5 grid: ${ROAD_KM} km of two-way road, ${LINE_KM} km of lane lines |
| driven | 50 traversals, ${KM} km |
| LSM elements | ${OBS} |
| LSM output | ${SIZE} (CBOR) |
| wall time | ${SECONDS_TAKEN} s (target < 60 s on one core) |
MD
cat "$SRC/docs/performance-simulate.md"
