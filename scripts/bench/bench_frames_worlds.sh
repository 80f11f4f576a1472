#!/usr/bin/env bash
# Frames level against the LSM level over many worlds (issue 33): per world, simulate the same
# drives at --level lsm and --level frames (camera, IMU, wheel, GPS), run the whole chain
# (scripts/crowd.mk: lsm-build per drive for frames, georef, align, aggregate, evaluate and the
# trust check), measure keyframe and element heights against the simulator's truth
# (bench_frames_height.py), check each frames row against issue 33's bounds and each map.osm
# with the real Lanelet2 library (issue 35). Writes the
# section between the frames-worlds markers of docs/performance-frames-chain.md.
# usage: scripts/bench/bench_frames_worlds.sh [BIN_DIR=build/bin]
# env: WORLDS (seed:grade of a procedural hill world with a 3 km outward route, or seed:FILE of
#      an OpenDRIVE / Lanelet2 map, whose routes are as long as its roads allow; default: the
#      eight worlds below), TRAVERSALS=20, WORK (kept when set; else scratch), MAPFUSE_SHARED
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"
shared=${MAPFUSE_SHARED:-$root/../shared}
maps="$shared/data/maps" esmini="$shared/data/maps/opendrive-esmini"
worlds=${WORLDS:-"11:0.05 3:0.08 3:$esmini/xodr__crest-curve.xodr \
3:$esmini/xodr__curves_elevation.xodr 3:$esmini/xodr__e6mini.xodr 3:$esmini/xodr__tunnels.xodr \
3:$maps/MONAEast.xodr 3:$maps/lanelet2_karlsruhe_mapping_example.osm"}
traversals=${TRAVERSALS:-20}
l2lib="${MAPFUSE_CACHE:-$HOME/.cache/mapfuse}/lanelet2-build"
work=${WORK:-$tmp}
mkdir -p "$work"
rows="$work/frames-worlds-rows.md"
: > "$rows"
for w in $worlds; do
  seed=${w%%:*} what=${w#*:}
  case $what in
    *.xodr | *.osm)
      [[ -f $what ]] || { echo "bench_frames_worlds: $what missing: skipped" >&2; continue; }
      world=(--map "$what") name=$(basename "$what") ;;
    *) world=(--world-grid-size 9 --world-hill-grade "$what") name="procedural seed $seed, grade $what" ;;
  esac
  for level in lsm frames; do
    tag="$level-$seed-$(basename "$what")"
    sim="$work/sim-$tag" out="$work/crowd-$tag"
    rm -rf "$sim" "$out"
    t0=$(date +%s)
    # LSMs as JSON: the height figures read align's output, which keeps its inputs' encoding
    "$bin/simulate" -q --level "$level" --format json --seed "$seed" "${world[@]}" \
      --route-outward 1 --route-length 3000 --routes 1 --traversals "$traversals" \
      --vehicles "$traversals" -o "$sim" > /dev/null
    t1=$(date +%s)
    if [[ $level == frames ]]; then src=(FRAMES_DIR="$sim/frames"); else src=(LSM_DIR="$sim/lsm"); fi
    # the trust check must not stop the bench: it is one of the figures
    make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" "${src[@]}" WORK="$out" \
      TRUTH="$sim/truth/vector_map.json" TRUTH_TRAJ="$sim/truth" MAX_UNTRUSTED_SHARE=1 \
      > "$out.log" 2>&1 || { tail -20 "$out.log" >&2; exit 1; }
    t2=$(date +%s)
    python3 "$root/scripts/bench/bench_frames_height.py" --aligned "$out/align" \
      --truth-traj "$sim/truth" --map "$out/aggregate/map.json" \
      --truth "$sim/truth/vector_map.json" > "$out/height.json"
    # The real Lanelet2 library on map.osm (tests/e2e/lanelet2_validate.sh builds and caches it)
    l2=n/a
    if [[ -x $l2lib/lanelet2_validate && -x $shared/tools/lanelet2/validate.sh ]]; then
      read -r lat lon < <(grep -m1 -o 'lat="[^"]*" lon="[^"]*"' "$out/aggregate/map.osm" |
        sed 's/lat="\([^"]*\)" lon="\([^"]*\)"/\1 \2/')
      if bash "$shared/tools/lanelet2/validate.sh" "$out/aggregate/map.osm" "$lat" "$lon" "$l2lib" \
        > "$out/aggregate/map.osm.validate.txt" 2>&1; then l2="exit 0"; else l2="exit $?"; fi
    fi
    python3 - "$name" "$level" "$out" "$sim" "$((t2 - t1))" "$work/lsm-lane-$seed-$(basename "$what")" \
      "$l2" >> "$rows" <<'PY'
import json, os, sys
name, level, out, sim, secs, lsm_file, l2 = sys.argv[1:]
ev = json.load(open(f"{out}/evaluate/evaluate.summary.json"))
h = json.load(open(f"{out}/height.json"))
chk = json.load(open(f"{out}/check.json"))
km = json.load(open(f"{sim}/simulate.summary.json"))["km_driven"] / max(1, len(h["keyframes"]["drives"]))
cls = {c["class"]: c for c in ev["maps"][0]["classes"] if c.get("truth_count", 1) != 0}
lane = cls.get("lane_line", {})
rel = lane.get("relative_precision_m")
if level == "lsm" and rel is not None:
    open(lsm_file, "w").write(str(rel))
short = {"lane_line": "lane", "stop_line": "stop", "ground_arrow": "arrow", "crosswalk": "cross",
         "traffic_sign": "sign", "traffic_light": "light", "pole": "pole"}
comp = " ".join(f"{short[k]} {c['completeness']:.2f}" for k, c in cls.items() if k in short)
red = max((c["redundancy"] for c in cls.values()), default=0.0)
kv, kh = h["keyframes"]["vertical_rms_m"], h["keyframes"]["horizontal_rms_m"]
eh = h["element_height"]["rms_m"]
# issue 33's bounds, frames level: lane rel. precision <= 0.06 m and <= 2x the LSM level;
# completeness >= 0.95 in every class; redundancy <= 0.03; keyframe vertical and element
# height RMS <= 0.3 m
verdict = "-"
if level == "frames":
    lsm_rel = float(open(lsm_file).read()) if os.path.exists(lsm_file) else None
    fails = []
    if rel is None or rel > 0.06 or (lsm_rel is not None and rel > 2 * lsm_rel):
        fails.append("lane precision")
    fails += [f"{short[k]} completeness" for k, c in cls.items() if k in short and c["completeness"] < 0.95]
    if red > 0.03:
        fails.append("redundancy")
    if kv is None or kv > 0.3:
        fails.append("keyframe height")
    if eh is None or eh > 0.3:
        fails.append("element height")
    verdict = "met" if not fails else "not met: " + ", ".join(fails)
f2 = lambda v: "n/a" if v is None else f"{v:.2f}"
print(f"| {name} | {level} | {km:.2f} | {'n/a' if rel is None else f'{rel:.3f}'} | {comp} | "
      f"{red:.3f} | {f2(kv)} / {f2(kh)} | {f2(eh)} | {', '.join(chk['untrusted']) or 'none'} | "
      f"{secs} | {l2} | {verdict} |")
PY
    echo "bench_frames_worlds: $name $level done ($((t2 - t0)) s)" >&2
  done
done
doc="$root/docs/performance-frames-chain.md"
section="$work/frames-worlds-section.md"
{
  echo "<!-- frames-worlds begin: written by scripts/bench/bench_frames_worlds.sh -->"
  echo "## Frames level against the LSM level over many worlds (issue 33)"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%MZ); load before: $load"
  echo "- machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "- command: \`scripts/bench/bench_frames_worlds.sh BIN_DIR\` (TRAVERSALS=$traversals): per"
  echo "  world \`simulate --level lsm|frames --route-outward 1 --route-length 3000 --routes 1"
  echo "  --traversals $traversals\` (one route that never loops back; on map worlds as long as the"
  echo "  roads allow), then \`make -j2 -f scripts/crowd.mk\` with the truth (lsm-build per drive"
  echo "  for frames, georef, align, aggregate, evaluate, the trust check)."
  echo "- columns: lane relative precision [m]; completeness per class the driven area holds;"
  echo "  the largest redundancy of any class; keyframe vertical / horizontal RMS against the true"
  echo "  pose [m]; element height RMS against the nearest true element of the class [m];"
  echo "  drives the trust check names; chain seconds (make, without simulate); issue 33's bounds"
  echo "  for the frames row (lane <= 0.06 m and <= 2x the LSM row, completeness >= 0.95,"
  echo "  redundancy <= 0.03, heights <= 0.3 m); Lanelet2: ../shared/tools/lanelet2/validate.sh on"
  echo "  map.osm (exit 0: no load error, no lanelet2_validate issue, a valid routing graph; n/a"
  echo "  where the library's cached build is absent)."
  echo
  echo "| world | level | km per drive | lane rel. precision m | completeness | max redundancy | keyframes vertical / horizontal m | element height m | untrusted | chain s | Lanelet2 validate.sh | bounds |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  cat "$rows"
  echo "<!-- frames-worlds end -->"
} > "$section"
python3 - "$doc" "$section" <<'PY'
import re, sys
doc, section = sys.argv[1:]
text = open(doc).read()
new = open(section).read()
pat = re.compile(r"<!-- frames-worlds begin.*?<!-- frames-worlds end -->\n", re.S)
text = pat.sub(lambda m: new, text) if pat.search(text) else text.rstrip("\n") + "\n\n" + new
open(doc, "w").write(text)
PY
cat "$section"
