#!/usr/bin/env bash
# Localisation on the map (issue 22, Song et al. 2023 Fig. 12): a procedural world driven 55
# times (simulate's defaults: 4 routes of 1.5 km, seed 42); the first 50 traversals build the map
# through the crowd chain (scripts/crowd.mk: georef -> align -> aggregate), the last 5 (their own
# per-traversal seeds, routes the map covers, never used to build it) are localised
# (a) on the aggregated map, (b) on the true map (the upper bound), at two levels:
#   LSM level: simulate's LSMs of the 5 drives, georeferenced in the map's origin;
#   frames level: the same 5 drives simulated as raw frames (simulate --level frames, same seed:
#   the same world, routes and sensor errors), lsm-build per drive, georef, localize --frames.
# Solves: full_drive (the default) and, at the LSM level, per_keyframe beside it. Errors against
# the truth as is and in the map's frame (--truth-map: the rigid map-to-truth transform).
# Localisation rate: localisations per second of the localisation loop (OMP_NUM_THREADS=1; the
# tool localises drives in parallel otherwise), median of 3 runs; load average recorded.
# The map's lateral error beside the bound its traversals' GPS sets: bench_map_bound.
# -> docs/performance-localize.md, docs/images/localize_errors.png
# usage: scripts/bench/bench_localize.sh [BIN_DIR=<root>/build/bin]   (about 5-10 minutes)
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"  # root, bin, tmp (removed on exit), load
traversals=50
held_out=5
seed=42

"$bin/simulate" -q --seed "$seed" --traversals $((traversals + held_out)) -o "$tmp/sim" > /dev/null
mkdir -p "$tmp/map_lsm" "$tmp/held_lsm" "$tmp/held_frames"
for f in "$tmp"/sim/lsm/*.cbor; do
  i=$(basename "$f" | sed -n 's/.*_trav\([0-9]*\)\..*/\1/p')
  if ((10#$i < traversals)); then ln -s "$f" "$tmp/map_lsm/"; else ln -s "$f" "$tmp/held_lsm/"; fi
done
make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$tmp/map_lsm" WORK="$tmp/work" map \
  > /dev/null
origin=$(cat "$tmp/work/origin.txt")
"$bin/georef" -q --origin "$origin" -o "$tmp/held_geo" "$tmp"/held_lsm/*.cbor > /dev/null
# frames level: the same drives as raw frames (observations only, no PNG masks)
"$bin/simulate" -q --seed "$seed" --traversals $((traversals + held_out)) --level frames \
  --frames-masks 0 -o "$tmp/simf" > /dev/null
for f in "$tmp"/held_lsm/*.cbor; do
  d=$(basename "$f" .lsm.cbor)
  ln -s "$tmp/simf/frames/$d" "$tmp/held_frames/$d"
  "$bin/lsm-build" -q --render 0 --format cbor -o "$tmp/frames_lsm/$d" "$tmp/simf/frames/$d" \
    > /dev/null
done
"$bin/georef" -q --origin "$origin" -o "$tmp/frames_geo" "$tmp"/frames_lsm/*/*.cbor > /dev/null

# run NAME MAP LEVEL [localize options]: three runs; the last summary and the median rate as JSON
run() {
  local name=$1 map=$2 level=$3 rates=()
  shift 3
  local inputs=("$tmp"/held_geo/*.cbor) truth="$tmp/sim/truth" extra=()
  if [[ $level == frames ]]; then
    inputs=("$tmp"/frames_geo/*.cbor) truth="$tmp/simf/truth" extra=(--frames "$tmp/held_frames")
  fi
  for rep in 1 2 3; do
    rm -rf "$tmp/loc_$name"
    OMP_NUM_THREADS=1 "$bin/localize" -q --map "$map" --truth-trajectories "$truth" \
      --truth-map "$tmp/sim/truth/vector_map.json" -o "$tmp/loc_$name" "${extra[@]}" "$@" \
      "${inputs[@]}" > /dev/null
    rates+=("$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['localisations_per_second_per_core'])" "$tmp/loc_$name/localize.summary.json")")
  done
  python3 - "$name" "$tmp/loc_$name/localize.summary.json" "${rates[@]}" <<'PY'
import json, statistics, sys
name, summary, *rates = sys.argv[1:]
s = json.load(open(summary))
print(json.dumps({"name": name, "rate": statistics.median(map(float, rates)), "summary": s}))
PY
}
agg="$tmp/work/aggregate/map.cbor" true_map="$tmp/sim/truth/vector_map.json"
rows="$tmp/rows.jsonl"
{
  run aggregated "$agg" lsm
  run aggregated_per_keyframe "$agg" lsm --solve per_keyframe
  run truth "$true_map" lsm
  run truth_per_keyframe "$true_map" lsm --solve per_keyframe
  run aggregated_frames "$agg" frames
  run truth_frames "$true_map" frames
} > "$rows"
first_png=$(ls "$tmp/loc_aggregated"/*.errors.png | head -1)
mkdir -p "$root/docs/images"
cp "$first_png" "$root/docs/images/localize_errors.png"

# the map's lateral error beside what its traversals' GPS allows (docs/performance-map-bound.md)
"$bin/bench_map_bound" --sim "$tmp/sim" --map "$agg" "$tmp"/map_lsm/*.cbor > "$tmp/bound.json"

python3 "$root/scripts/bench/localize_report.py" "$rows" "$root/docs/performance-localize.md" \
  "$load" "$traversals" "$held_out" "$seed" "$(basename "$first_png" .errors.png)" \
  "$tmp/bound.json"
