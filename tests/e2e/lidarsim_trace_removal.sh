#!/usr/bin/env bash
# Trace removal against the simulator's truth (issue 8's acceptance: >= 95 % of moving-car voxels
# removed, >= 95 % of parked-car voxels kept): simulate-lidar seed 901 (a lead car still in view at
# the end of the drive, traces passing parked cars: the hardest of the seeds in
# docs/lidar-ground-truth.md), lidar-semantic-map, evaluate voxels. Issue 8's figures are for the
# refinement alone (--classifier-dir none, as measured then); the default run adds error
# minimisation (issue 24), which drops mislabelled clusters on parked cars too and so leaves
# holes in them: 94.6 % of the parked-car voxels kept on this seed (95.1 % without it), hence
# its own bound below.
set -euo pipefail
bin="$MAPFUSE_BIN_DIR"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
drive=$("$bin/simulate-lidar" -o "$tmp/sim" --seed 901 --drive 901 --frames 30 --quiet)
check() {  # name min_parked_kept_share [lidar-semantic-map args]
  local name=$1 parked=$2
  shift 2
  "$bin/lidar-semantic-map" "$drive" -o "$tmp/$name" --quiet "$@" > /dev/null
  "$bin/evaluate" voxels --drive "$drive" --map "$tmp/$name/map.ply" -o "$tmp/eval_$name" \
    --quiet > /dev/null
  python3 - "$tmp/eval_$name/voxels.json" "$name" "$parked" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))["trace_removal"]
kMinShare = 0.95  # issue 8
kMinParked = float(sys.argv[3])
print(f"{sys.argv[2]}: moving removed {t['moving_removed_share']:.4f} of {t['moving_truth_voxels']}, "
      f"parked kept {t['parked_kept_share']:.4f} of {t['parked_truth_voxels']}")
assert t["moving_truth_voxels"] > 1000 and t["parked_truth_voxels"] > 1000, t
assert t["moving_removed_share"] >= kMinShare, t
assert t["parked_kept_share"] >= kMinParked, t
PY
}
check refinement 0.95 --classifier-dir none
check default 0.94
echo "lidarsim_trace_removal: ok"
