#!/usr/bin/env bash
# Regenerates the default error-minimisation classifiers (one OpenCV random forest per label,
# rtrees_<label>.yml, plain YAML text) with one command, from synthetic labelled drives with
# fixed seeds: simulate-lidar (docs/lidar-ground-truth.md), then `lidar-semantic-map train`.
#
# usage: scripts/train-classifiers.sh [BIN_DIR=build/bin] [OUT_DIR=models/lidar-classifiers]
# env:   SEEDS="101 102 103 104"  FRAMES=40  WORK=<scratch folder, default a temp dir>
# Same seeds and binaries => same drives => same forests (the forests' own seed is fixed).
set -euo pipefail
bin=${1:-build/bin}
out=${2:-models/lidar-classifiers}
seeds=${SEEDS:-"101 102 103 104"}
frames=${FRAMES:-40}
work=${WORK:-$(mktemp -d)}
for tool in simulate-lidar lidar-semantic-map; do
  [ -x "$bin/$tool" ] || { echo "train-classifiers: $bin/$tool not built" >&2; exit 2; }
done
"$bin/lidar-semantic-map" train --help > /dev/null 2>&1 || {
  echo "train-classifiers: this lidar-semantic-map has no 'train' subcommand" >&2; exit 2; }

drives=()
for seed in $seeds; do
  name=$(printf 'train%s' "$seed")
  echo "train-classifiers: simulating seed $seed ($frames frames)" >&2
  drives+=("$("$bin/simulate-lidar" -o "$work" --seed "$seed" --drive "$name" \
              --frames "$frames" --quiet)")
done
echo "train-classifiers: training on ${#drives[@]} drives -> $out" >&2
"$bin/lidar-semantic-map" train -o "$out" "${drives[@]}"
echo "$out"
