#!/usr/bin/env bash
# Where the aggregated map's absolute error comes from (issue 22): per simulate seed, 50
# traversals of the localisation bench's world (simulate defaults: procedural, 4 routes of
# 1.5 km; seed 42 is bench_localize.sh's map) through the crowd chain (scripts/crowd.mk map),
# then bench_map_bound: the map's lane lines across the road against the true ones, beside
#   bound   the mean GPS error of the map's traversals that drove past each point (100 m stretch),
#   global  the mean GPS error of all of them (a map of exact shape placed on all the GPS),
#   georef / align: where those stages put the keyframes and lane-line points (their mean
#           over the traversals at each point).
# Ablations on the same georeferenced drives (align + aggregate + evaluate): the oracle (each
# drive's own mean GPS error taken off its georeferenced keyframes, the mean over all drives
# kept: is the map's non-rigid error the drives' GPS biases?), align --method sgicp (no GBA),
# --gba-max-partners 1, --odom-sigma-per-m 0.003 (stiffer odometry), with the issue 18 quality
# figures (relative precision, completeness, redundancy) beside.
# -> docs/performance-map-bound.md
# usage: scripts/bench/bench_map_bound.sh [BIN_DIR=<root>/build/bin] [SEED...]   (~1-2 min a seed)
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"  # root, bin, tmp (removed on exit), load
shift || true
seeds=("$@")
[[ ${#seeds[@]} -gt 0 ]] || seeds=(42 1 2 3 7)
traversals=50
rows="$tmp/rows.jsonl"

# variant NAME SEED_DIR GEOREF_DIR [align options]: align + aggregate + evaluate + bench_map_bound
variant() {
  local name=$1 d=$2 geo=$3
  shift 3
  "$bin/align" -q "$@" -o "$d/$name/align" $(find "$geo" -name '*.lsm.cbor' | sort) > /dev/null
  "$bin/aggregate" -q -o "$d/$name/aggregate" "$d/$name"/align/*.lsm.cbor > /dev/null
  result "$name" "$d" "$d/$name/aggregate/map.cbor" "$d/$name/align" \
    --stage "georef=$geo" --stage "align=$d/$name/align"
}
# result NAME SEED_DIR MAP ALIGN_DIR [bench_map_bound options]: one JSON row
result() {
  local name=$1 d=$2 map=$3 aligned=$4
  shift 4
  "$bin/evaluate" map -q --map "$map" --truth "$d/sim/truth/vector_map.json" \
    --truth-trajectories "$d/sim/truth" --lsm "$aligned"/*.lsm.cbor -o "$d/$name/evaluate" \
    > /dev/null
  "$bin/bench_map_bound" --sim "$d/sim" --map "$map" "$@" "$d"/sim/lsm/*.cbor \
    > "$d/$name/bound.json"
  python3 - "$name" "$seed" "$d/$name/bound.json" "$d/$name/evaluate/evaluate.summary.json" \
    "$aligned/align.summary.json" <<'PY'
import json, sys
name, seed, bound, ev, al = sys.argv[1:]
classes = {c["class"]: c for c in json.load(open(ev))["maps"][0]["classes"]}
lane = classes["lane_line"]
print(json.dumps({"name": name, "seed": int(seed), "bound": json.load(open(bound)),
                  "lane_abs_mean_m": lane["absolute_error"]["mean"],
                  "lane_rel_precision_m": lane["relative_precision_m"],
                  "lane_completeness": lane["completeness"],
                  "min_class_completeness": min(c["completeness"] for c in classes.values()),
                  "max_redundancy": max(c["redundancy"] for c in classes.values()),
                  "align_seconds": json.load(open(al))["seconds"]}))
PY
}

for seed in "${seeds[@]}"; do
  d="$tmp/seed$seed"
  "$bin/simulate" -q --seed "$seed" --traversals "$traversals" -o "$d/sim" > /dev/null
  make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$d/sim/lsm" WORK="$d/work" map \
    > /dev/null
  mkdir -p "$d/default"
  result default "$d" "$d/work/aggregate/map.cbor" "$d/work/align" \
    --stage "georef=$d/work/georef" --stage "align=$d/work/align" \
    --csv "$d/default/cells.csv" >> "$rows"
  [[ $seed == 42 ]] && cp "$d/default/cells.csv" "$tmp/cells42.csv"
  # the oracle: every drive's own constant GPS error taken off its georeferenced keyframes
  # (their mean over all drives stays), then the default align
  "$bin/bench_map_bound" --sim "$d/sim" --map "$d/work/aggregate/map.cbor" \
    --debias-in "$d/work/georef" --debias-out "$d/oracle_georef" "$d"/sim/lsm/*.cbor > /dev/null
  variant oracle "$d" "$d/oracle_georef" >> "$rows"
  variant sgicp "$d" "$d/work/georef" --method sgicp >> "$rows"
  variant partners1 "$d" "$d/work/georef" --gba-max-partners 1 >> "$rows"
  variant odometry0.003 "$d" "$d/work/georef" --odom-sigma-per-m 0.003 >> "$rows"
done
python3 "$root/scripts/bench/map_bound_report.py" "$rows" "$root/docs/performance-map-bound.md" \
  "$load" "$traversals" "$tmp/cells42.csv"
