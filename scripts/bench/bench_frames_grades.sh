#!/usr/bin/env bash
# Heights on graded worlds at the frames level (issue 33): per world, simulate raw drives
# (camera, IMU, wheel, GPS) on a hilly procedural world along one outward route that never loops
# back, run the whole chain (scripts/crowd.mk: lsm-build per drive, georef, align, aggregate,
# evaluate, the trust check) and measure keyframe and element heights against the simulator's
# truth (bench_frames_height.py). Optionally one traversal gets an IMU mounted pitched
# (INJECT_PITCH_TRAVERSAL): the trust check must name that drive. Prints one Markdown row per
# world; docs/performance-frames-grades.md keeps the rows with machine, command and date.
# usage: scripts/bench/bench_frames_grades.sh [BIN_DIR=build/bin]
# env: WORLDS="7:0.08 11:0.05" (seed:grade of a procedural world, or seed:FILE.xodr|.osm of a
#      map world, e.g. 3:../shared/data/maps/opendrive-esmini/xodr__crest-curve.xodr, whose
#      routes are as long as its roads allow), TRAVERSALS=4, ROUTE_LENGTH=3000, GRID=9,
#      INJECT_PITCH_TRAVERSAL=-1, LEVEL=frames (or lsm: the same drives observed at the LSM
#      level, the row the frames level is compared with), WORK (kept when set; else scratch)
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"
worlds=${WORLDS:-"7:0.08"}
traversals=${TRAVERSALS:-4}
route_length=${ROUTE_LENGTH:-3000}
grid=${GRID:-9}
inject=${INJECT_PITCH_TRAVERSAL:--1}
level=${LEVEL:-frames}
case $level in frames) input=FRAMES_DIR ;; lsm) input=LSM_DIR ;; *) echo "LEVEL: frames or lsm" >&2; exit 2 ;; esac
work=${WORK:-$tmp}
echo "| seed | grade | km per drive | drives | keyframes vertical RMS m (per drive) | keyframes horizontal RMS m | element height RMS / mean m | lane completeness / rel. precision m | untrusted drives | seconds |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for w in $worlds; do
  seed=${w%%:*} grade=${w#*:}
  world=(--world-grid-size "$grid" --world-hill-grade "$grade")
  case $grade in *.xodr | *.osm) world=(--map "$grade") grade=$(basename "$grade") ;; esac
  sim="$work/sim-$level-$seed-$grade" out="$work/crowd-$level-$seed-$grade"
  rm -rf "$sim" "$out"
  t0=$(date +%s)
  # LSMs as JSON: the height figures read align's output, which keeps its inputs' encoding
  "$bin/simulate" -q --level "$level" --format json --seed "$seed" "${world[@]}" \
    --route-outward 1 --route-length "$route_length" --routes 1 \
    --traversals "$traversals" --vehicles "$traversals" --inject-pitch-traversal "$inject" \
    -o "$sim" > /dev/null
  # the trust check must not stop the bench: it is one of the figures
  make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" "$input=$sim/$level" WORK="$out" \
    TRUTH="$sim/truth/vector_map.json" TRUTH_TRAJ="$sim/truth" MAX_UNTRUSTED_SHARE=1 \
    > "$out.log" 2>&1 || { tail -20 "$out.log"; exit 1; }
  secs=$(($(date +%s) - t0))
  python3 "$root/scripts/bench/bench_frames_height.py" --aligned "$out/align" \
    --truth-traj "$sim/truth" --map "$out/aggregate/map.json" \
    --truth "$sim/truth/vector_map.json" > "$out/height.json"
  python3 - "$seed" "$grade" "$secs" "$out" "$sim" <<'PY'
import glob, json, sys
seed, grade, secs, out, sim = sys.argv[1:]
h = json.load(open(f"{out}/height.json"))
ev = json.load(open(f"{out}/evaluate/evaluate.summary.json"))
chk = json.load(open(f"{out}/check.json"))
lane = {c["class"]: c for c in ev["maps"][0]["classes"]}.get("lane_line", {})
kf = h["keyframes"]
drives = kf["drives"].values() if isinstance(kf["drives"], dict) else kf["drives"]
per = " / ".join("n/a" if d['vertical_rms_m'] is None else f"{d['vertical_rms_m']:.2f}" for d in drives)
eh = h["element_height"]
stats = json.load(open(f"{sim}/simulate.summary.json"))
km = stats["km_driven"] / max(1, len(kf["drives"]))  # per drive: one route
rel = lane.get("relative_precision_m")
f2 = lambda v: "n/a" if v is None else f"{v:.2f}"  # a world with nothing of that kind
sg = lambda v: "n/a" if v is None else f"{v:+.2f}"
print(f"| {seed} | {grade} | {km:.2f} | {len(kf['drives'])} | {f2(kf['vertical_rms_m'])} ({per}) | "
      f"{f2(kf['horizontal_rms_m'])} | "
      f"{f2(eh['rms_m'])} / {sg(eh['mean_m'])} | {lane.get('completeness', 0):.2f} / "
      f"{rel if rel is None else round(rel, 3)} | {', '.join(chk['untrusted']) or 'none'} | {secs} |")
PY
done
echo
echo "load: $load; $(nproc) cores; $(date -u +%Y-%m-%dT%H:%MZ)"
