#!/usr/bin/env bash
# Generates the default error-minimisation classifiers (one OpenCV random forest per label,
# rtrees_<label>.yml, plain YAML text, and thresholds.json) with one command, from synthetic
# labelled drives with fixed seeds: simulate-lidar (docs/lidar-ground-truth.md), then
# `lidar-semantic-map train TRAIN... --validation VALIDATION...`: the validation drives choose
# each label's threshold and drop the forests that cost their label IoU
# (lidar/forest_thresholds.hpp). Writes provenance.json beside the forests: the command, seeds,
# frames, code commit, date, and the size and SHA-256 of every generated file.
# The build runs it (target lidar_classifiers -> build/models/lidar-classifiers, the folder
# `--classifier-dir auto` finds).
#
# usage: scripts/train-classifiers.sh [BIN_DIR=build/bin] [OUT_DIR=models/lidar-classifiers]
# env:   SEEDS="101 102 103 104"  VALIDATION_SEEDS="105 106 107"  FRAMES=40
#        WORK=<scratch folder, default a temp dir, removed at the end>
# Same seeds and binaries => same drives => same forests, byte for byte (the forests' own seed
# is fixed); only provenance.json's date and commit change.
set -euo pipefail
bin=${1:-build/bin}
out=${2:-models/lidar-classifiers}
seeds=${SEEDS:-"101 102 103 104"}
val_seeds=${VALIDATION_SEEDS:-"105 106 107"}
frames=${FRAMES:-40}
root=$(cd "$(dirname "$0")/.." && pwd)
if [[ -n "${WORK:-}" ]]; then
  work=$WORK
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
for tool in simulate-lidar lidar-semantic-map; do
  [ -x "$bin/$tool" ] || { echo "train-classifiers: $bin/$tool not built" >&2; exit 2; }
done
"$bin/lidar-semantic-map" train --help 2>/dev/null | grep -q -- --validation || {
  echo "train-classifiers: this lidar-semantic-map has no 'train --validation'" >&2; exit 2; }

simulate() {  # seed -> drive folder (its own output folder: a run locks the one it writes)
  "$bin/simulate-lidar" -o "$work/sim-$1" --seed "$1" --drive "$(printf 'train%s' "$1")" \
    --frames "$frames" --quiet
}
# The drives are independent (one seed each): JOBS of them at a time (default: the cores), each
# writing its folder's name to a file, read back in seed order (same forests whatever JOBS).
mkdir -p "$work"
jobs=${JOBS:-$(nproc 2>/dev/null || echo 1)}
running=()
for seed in $seeds $val_seeds; do
  echo "train-classifiers: simulating seed $seed ($frames frames)" >&2
  simulate "$seed" > "$work/drive-$seed.txt" &
  running+=($!)
  if ((${#running[@]} >= jobs)); then
    wait "${running[0]}" || { echo "train-classifiers: simulate-lidar failed" >&2; exit 1; }
    running=("${running[@]:1}")
  fi
done
for pid in "${running[@]}"; do
  wait "$pid" || { echo "train-classifiers: simulate-lidar failed" >&2; exit 1; }
done
drives=() held=()
for seed in $seeds; do drives+=("$(cat "$work/drive-$seed.txt")"); done
for seed in $val_seeds; do held+=("$(cat "$work/drive-$seed.txt")"); done
echo "train-classifiers: training on ${#drives[@]} drives, validating on ${#held[@]} -> $out" >&2
"$bin/lidar-semantic-map" train -o "$out" "${drives[@]}" --validation "${held[@]}" --quiet \
  > /dev/null

commit=$(git -C "$root" rev-parse HEAD 2>/dev/null || echo unknown)
if [[ "$commit" != unknown ]] && ! git -C "$root" diff --quiet HEAD -- libmapfuse apps scripts \
  2>/dev/null; then
  commit="$commit+uncommitted changes"
fi
python3 - "$out" "$commit" "$seeds" "$val_seeds" "$frames" <<'PY'
import datetime, hashlib, json, os, sys
out, commit, seeds, val_seeds, frames = sys.argv[1:]
files = {}
for name in sorted(os.listdir(out)):
    if name.startswith("rtrees_") or name == "thresholds.json":
        data = open(os.path.join(out, name), "rb").read()
        files[name] = {"bytes": len(data), "sha256": hashlib.sha256(data).hexdigest()}
summary = json.load(open(os.path.join(out, "lidar-semantic-map-train.summary.json")))
record = {
    "format": "mapfuse.lidar_forest_provenance",
    "generator": "scripts/train-classifiers.sh (simulate-lidar, then lidar-semantic-map train)",
    "command": f'SEEDS="{seeds}" VALIDATION_SEEDS="{val_seeds}" FRAMES={frames} '
               "scripts/train-classifiers.sh BIN_DIR OUT_DIR",
    "training_seeds": [int(s) for s in seeds.split()],
    "validation_seeds": [int(s) for s in val_seeds.split()],
    "frames_per_drive": int(frames),
    "code_commit": commit,
    "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
    "labels": {k: v.get("validation", {"forest_used": v["trained"]})
               for k, v in summary["labels"].items()},
    "files": files,
}
json.dump(record, open(os.path.join(out, "provenance.json"), "w"), indent=2)
PY
rm -rf "$out/semantics_cache"
echo "$out"
