#!/usr/bin/env bash
# Issue 36: the 100 km network batch (50 traversals over 8 routes of 25 km on a 17 x 17 grid,
# 119 road km, 1150 driven km) through the Snakefile on a private single-node Slurm, untiled and
# in tiles, against a local make run of the same batch: tests/e2e/slurm_cluster.sh with the
# bench's batch (it checks every map, aligned / balanced LSM and evaluate summary byte for byte).
# Prints the e2e's progress lines (seconds since its start) and the total.
# usage: scripts/bench/bench_slurm_scale.sh [BIN_DIR=<root>/build/bin]
# env: TILE_SIZE (m, default 3000), SIMULATE (simulate's options, default the 100 km batch)
# Needs root (slurmd) and scripts/install-deps.sh's Slurm, munge and Snakemake. About 15 min.
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"  # root, bin, tmp (removed on exit), load
t0=$SECONDS
MAPFUSE_BIN_DIR="$bin" MAPFUSE_SOURCE_DIR="$root" MAPFUSE_REQUIRE_SLURM=1 \
  MAPFUSE_SLURM_TILE_SIZE="${TILE_SIZE:-3000}" \
  MAPFUSE_SLURM_SIMULATE="${SIMULATE:---traversals 50 --routes 8 --route-length 25000 --world-grid-size 17}" \
  bash "$root/tests/e2e/slurm_cluster.sh"
echo "bench_slurm_scale: passed in $((SECONDS - t0)) s ($(date -u '+%Y-%m-%d %H:%M UTC'), load $(cut -d' ' -f1-3 /proc/loadavg))"
