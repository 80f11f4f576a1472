#!/usr/bin/env bash
# Issue-4 acceptance figures: georef + align (icp | sicp | sgicp | gba_sgicp) on simulate data,
# the procedural world and the real Karlsruhe Lanelet2 map, N traversals (default 20), default
# low-cost noise. Element spread across traversals, element absolute error and keyframe ATE
# against the simulator's truth (bench_fusion_errors), time per phase.
# Writes docs/performance-fusion-accuracy.md. Usage: bench_fusion_accuracy.sh [BIN_DIR] [N]
# env: KARLSRUHE_SEEDS="1 2 3 4 5 6 7" (further simulate seeds of the one-route Karlsruhe world,
# summarised as means over all seeds with the default 42; empty: none)
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"  # root, bin, tmp (removed on exit), load
n="${2:-20}"
shared="${MAPFUSE_SHARED:-$root/../shared}"
osm="$shared/data/maps/lanelet2_karlsruhe_mapping_example.osm"
out="$root/docs/performance-fusion-accuracy.md"

now() { date +%s.%N; }
row() {  # world label, folder
  local w=$1 dir=$2
  python3 - "$w" "$dir" <<'PY'
import json, sys
w, d = sys.argv[1], sys.argv[2]
geo = json.load(open(f"{d}/err_georef.json"))
def line(name, e, secs):
    ratio = geo["element_spread_m"] / e["element_spread_m"] if e["element_spread_m"] > 0 else float("inf")
    print(f"| {w} | {name} | {e['element_spread_m']:.3f} | {e['element_spread_median_m']:.3f} | "
          f"{ratio:.1f}x | {e['element_abs_m']:.3f} | {e['ate_mean_m']:.3f} | {secs} |")
line("georef", geo, open(f"{d}/t_georef").read().strip())
for m in ["icp", "sicp", "sgicp", "gba_sgicp"]:
    e = json.load(open(f"{d}/err_{m}.json"))
    s = json.load(open(f"{d}/al_{m}/align.summary.json"))
    kept = f"{s['constraints_pcm_kept']}/{s['constraints_proposed']}"
    line(f"{m} (PCM kept {kept})", e, open(f"{d}/t_{m}").read().strip())
print(f"| {w} | mean GPS bias of the drives | | | | {geo['gps_bias_mean_m']:.3f} | | |")
PY
}

seeds_extra=${KARLSRUHE_SEEDS-"1 2 3 4 5 6 7"}

run_world() {  # label, extra simulate args...
  local w=$1; shift
  local d="$tmp/$w"
  mkdir -p "$d"
  "$bin/simulate" -q --traversals "$n" -o "$d/sim" "$@" >/dev/null
  local t0; t0=$(now)
  "$bin/georef" -q "$d"/sim/lsm/*.lsm.cbor -o "$d/geo" >/dev/null
  python3 -c "print(f'{$(now) - $t0:.1f}')" > "$d/t_georef"
  "$bin/bench_fusion_errors" --sim "$d/sim" "$d"/geo/*.lsm.cbor > "$d/err_georef.json"
  for m in icp sicp sgicp gba_sgicp; do
    t0=$(now)
    "$bin/align" -q --method "$m" "$d"/geo/*.lsm.cbor -o "$d/al_$m" >/dev/null
    python3 -c "print(f'{$(now) - $t0:.1f}')" > "$d/t_$m"
    "$bin/bench_fusion_errors" --sim "$d/sim" "$d"/al_$m/*.lsm.cbor > "$d/err_$m.json"
  done
  python3 -c "import json; s = json.load(open('$d/sim/simulate.summary.json')); \
print(f\"{s['km_driven']:.1f} km driven, {s['lane_km']:.1f} km of lanes\")" > "$d/road_km"
}

run_world procedural
worlds="procedural"
if [ -f "$osm" ]; then
  # The map's drivable lanelets form disconnected patches (longest route ~300 m): with the
  # default 4 routes each road gets only n/4 of the traversals, so the issue-4 figure ("n
  # traversals") drives one route n times; the default split is reported alongside.
  run_world karlsruhe --map "$osm" --routes 1
  run_world karlsruhe-4-routes --map "$osm"
  worlds="procedural karlsruhe karlsruhe-4-routes"
  for s in $seeds_extra; do run_world "karlsruhe-seed$s" --map "$osm" --routes 1 --seed "$s"; done
else
  echo "bench_fusion_accuracy: $osm absent, Karlsruhe rows skipped" >&2
fi

{
  echo "# Performance: alignment accuracy (georef + align on simulate data)"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "- machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "- command: \`scripts/bench/bench_fusion_accuracy.sh BIN_DIR $n\`"
  echo "- input: \`simulate --traversals $n\` (default low-cost noise: GPS bias 1-3 m random walk,"
  echo "  multipath outliers, 1 % wheel scale, gyro drift), procedural world and the Karlsruhe"
  echo "  Lanelet2 map; \`georef\`, then \`align --method M\` with the default configs/align.json."
  echo "- karlsruhe: \`--routes 1\`, all $n traversals on one route (the map's drivable lanelets form"
  echo "  disconnected patches, routes of ~300 m); karlsruhe-4-routes: the default 4 routes, so each"
  echo "  road is driven about $((n / 4)) times."
  for w in $worlds; do echo "- $w: $(cat "$tmp/$w/road_km")"; done
  echo
  echo "Spread: per true element (lane lines in 20 m pieces) seen by >= 2 drives, RMS distance of"
  echo "the per-drive mean offsets to their mean, averaged; abs: mean horizontal distance of an"
  echo "element observation to its true element; ATE: mean over drives of the keyframe RMS"
  echo "position error (eval/truth_errors.hpp). Time: wall seconds of the stage, 2 threads."
  echo
  echo "| world | method | spread mean [m] | spread median [m] | spread shrink vs georef | abs error [m] | keyframe ATE [m] | time [s] |"
  echo "|---|---|---|---|---|---|---|---|"
  for w in $worlds; do row "$w" "$tmp/$w"; done
  if [ -f "$osm" ] && [ -n "$seeds_extra" ]; then
    echo
    echo "Karlsruhe, one route, $n traversals, simulate seeds 42 (above) and $seeds_extra: per method,"
    echo "the mean over seeds of each figure, and the smallest per-seed spread shrink."
    echo
    echo "| method | spread mean [m] | spread shrink (mean spreads) | smallest per-seed shrink | abs error [m] | keyframe ATE [m] | mean GPS bias [m] |"
    echo "|---|---|---|---|---|---|---|"
    python3 - "$tmp" karlsruhe $(for s in $seeds_extra; do echo "karlsruhe-seed$s"; done) <<'PY'
import json, sys
tmp, worlds = sys.argv[1], sys.argv[2:]
load = lambda w, m: json.load(open(f"{tmp}/{w}/err_{m}.json"))
mean = lambda xs: sum(xs) / len(xs)
geo = [load(w, "georef") for w in worlds]
for m in ["georef", "icp", "sicp", "sgicp", "gba_sgicp"]:
    e = [load(w, m) for w in worlds]
    spread = [x["element_spread_m"] for x in e]
    shrink = sum(g["element_spread_m"] for g in geo) / sum(spread)
    worst = min(g["element_spread_m"] / x for g, x in zip(geo, spread))
    print(f"| {m} | {mean(spread):.3f} | {shrink:.1f}x | {worst:.1f}x | "
          f"{mean([x['element_abs_m'] for x in e]):.3f} | {mean([x['ate_mean_m'] for x in e]):.3f} | "
          f"{mean([g['gps_bias_mean_m'] for g in geo]):.3f} |")
PY
  fi
} > "$out"
cat "$out"
