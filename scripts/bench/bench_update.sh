#!/usr/bin/env bash
# Map update (issue 34, docs/update.md): change detection against the number of new traversals,
# over several worlds, and the cost of an update against the size of the map.
#   scripts/bench/bench_update.sh BIN_DIR [WORK]
# Per world: OLD traversals of the world "before" -> map (scripts/crowd.mk, in the truth's
# frame); the same world with true changes ("after", simulate --change-*), whose traversals
# OLD.. are the new drives (seeds the old drives did not have); for N new traversals
# `make -f crowd.mk UPDATE_MAP=map.json LSM_DIR=<N new LSMs>` (georef in the map's frame,
# update); the report's ids renamed to the truth's (scripts/changes-to-truth-ids.py), scored by
# `evaluate changes`. At N = NREBUILD the updated map is evaluated against the "after" truth
# beside a full rebuild from all traversals of the "after" world. Frames level: the new drives
# go through lsm-build first (not timed in the update column). Then the cost rows: maps of
# growing road length, 5 new drives of 2 km, update against a full rebuild.
# Writes docs/performance-update.md (and a PNG of F1 against N) between its markers.
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"
work=${2:-$tmp}
mkdir -p "$work"
shared=${MAPFUSE_SHARED:-$root/../shared}
maps=$shared/data/maps
OLD=${OLD:-50}
NS=${NS:-"1 2 3 5 10 20"}
NREBUILD=${NREBUILD:-10}
SIZES=${SIZES:-"2000 5000 10000 20000"}
doc=$root/docs/performance-update.md
rows=$work/rows.tsv
[[ -n ${KEEP_ROWS:-} ]] || : > "$rows"  # KEEP_ROWS=1: add to an earlier run's rows in WORK
cost=$work/cost.tsv
: > "$cost"
nmax=0
for n in $NS; do ((n > nmax)) && nmax=$n; done
started=$(date -u +%Y-%m-%dT%H:%MZ)
EIGHT=(--change-removed 8 --change-added 8 --change-moved 8 --change-restriped 8
  --change-retyped 8 --change-seed 3)

origin_of() {  # the simulation's ENU origin as lat,lon,alt
  python3 -c 'import json,sys; o=json.load(open(sys.argv[1]))["origin"]; print("%s,%s,%s" % (o["lat"], o["lon"], o["alt"]))' "$1/simulate.summary.json"
}

# world NAME LEVEL OLD "SIM ARGS" "CHANGE ARGS" (only worlds whose name matches ONLY, a regex)
world() {
  local name=$1 level=$2 old=$3
  [[ -z ${ONLY:-} || $name =~ $ONLY ]] || return 0
  read -r -a sim <<< "$4"
  read -r -a changes <<< "$5"
  local w=$work/$(echo "$name-$level" | tr ' ,/()' '_____')
  rm -rf "$w" && mkdir -p "$w"
  echo "bench_update: $name, $level level" >&2
  "$bin/simulate" -q "${sim[@]}" --level "$level" --traversals "$old" -o "$w/before" > /dev/null
  if ! "$bin/simulate" -q "${sim[@]}" --level "$level" --traversals $((old + nmax)) \
    "${changes[@]}" -o "$w/after" > /dev/null 2> "$w/after.err"; then
    # a world without room for the changes asked: a row that says so, not a stopped bench
    printf '%s\t%s\t-\t-\t-\t-\t%s\t-\t-\t-\t-\t-\n' "$name" "$level" \
      "no changed world: $(tail -1 "$w/after.err" | sed 's/.*error: //; s/|/\\|/g')" >> "$rows"
    return 0
  fi
  local origin
  origin=$(origin_of "$w/before")
  local src=(LSM_DIR="$w/before/lsm")
  [[ $level == frames ]] && src=(FRAMES_DIR="$w/before/frames")
  make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" "${src[@]}" WORK="$w/crowd" ORIGIN="$origin" \
    map > "$w/crowd.log" 2>&1 || { tail -20 "$w/crowd.log" >&2; return 1; }
  # the new drives' LSMs (frames: lsm-build, two at a time)
  mkdir -p "$w/new"
  local i d
  for ((i = old; i < old + nmax; ++i)); do
    d=$(printf 'trav%03d' "$i")
    if [[ $level == frames ]]; then
      ls -d "$w/after/frames/"*"_$d"
    else
      cp "$w/after/lsm/"*"_$d".lsm.* "$w/new/"
    fi
  done > "$w/new-frames.txt"
  if [[ $level == frames ]]; then
    xargs -P 2 -I{} sh -c '"$0" -q -o "$1/lsmb/$(basename {})" {} > /dev/null && mv "$1/lsmb/$(basename {})/$(basename {}).lsm.json" "$1/new/"' \
      "$bin/lsm-build" "$w" < "$w/new-frames.txt"
  fi
  local files=()
  # in traversal order (trav050, trav051, ...; the vehicle prefix would group them by vehicle,
  # and traversal i drives route i % routes)
  mapfile -t files < <(for f in "$w/new/"*; do echo "$(basename "$f" | sed 's/.*_trav//') $f"; done |
    sort | cut -d' ' -f2-)
  for n in $NS; do
    local t=$w/T$n u=$w/upd$n
    rm -rf "$t" "$u" && mkdir -p "$t"
    cp "${files[@]:0:$n}" "$t/"
    local t0 t1
    t0=$(date +%s.%N)
    make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" UPDATE_MAP="$w/crowd/aggregate/map.json" \
      LSM_DIR="$t" WORK="$u" > "$u.log" 2>&1 || { tail -20 "$u.log" >&2; return 1; }
    t1=$(date +%s.%N)
    python3 "$root/scripts/changes-to-truth-ids.py" "$u/update/changes.json" \
      "$w/crowd/aggregate/map.json" "$w/before/truth/vector_map.json" "$u/ids.json" 2> /dev/null
    "$bin/evaluate" changes -q --detected "$u/ids.json" --truth "$w/after/truth/changes.json" \
      --before "$w/before/truth/vector_map.json" -o "$u/ev" > /dev/null
    local quality=-
    if ((n == NREBUILD)) && [[ $level == lsm ]]; then
      # the updated map and a full rebuild from every traversal of the "after" world
      "$bin/evaluate" map -q --map "$u/update/map.json" --truth "$w/after/truth/vector_map.json" \
        -o "$u/ev-map" > /dev/null
      make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$w/after/lsm" WORK="$w/rebuild" \
        ORIGIN="$origin" TRUTH="$w/after/truth/vector_map.json" evaluate > "$w/rebuild.log" 2>&1 ||
        { tail -20 "$w/rebuild.log" >&2; return 1; }
      quality="$u/ev-map/evaluate.summary.json $w/rebuild/evaluate/evaluate.summary.json"
    fi
    python3 - "$name" "$level" "$n" "$u" "$(echo "$t1 - $t0" | bc)" "$quality" >> "$rows" <<'PY'
import json, sys
name, level, n, u, secs, quality = sys.argv[1:]
s = json.load(open(f"{u}/ev/change-scores.json"))
summ = json.load(open(f"{u}/update/update.summary.json"))
f1 = lambda d: "-" if d.get("f1") is None else "%.2f" % d["f1"]
kinds = ["removed", "added", "moved", "restriped", "retyped"]
per = " / ".join(f1(s["by_kind"].get(k, {})) for k in kinds)
fr = s["false_removals"]
o = s["overall"]
q = "-"
if quality != "-":
    up, rb = quality.split()
    def lane(p):
        cl = {c["class"]: c for c in json.load(open(p))["maps"][0]["classes"]}
        low = min(v["completeness"] for v in cl.values())
        red = max(v["redundancy"] for v in cl.values())
        rp = cl["lane_line"]["relative_precision_m"]
        return "%s / %.2f / %.2f" % ("-" if rp is None else "%.3f" % rp, low, red)
    q = "%s vs %s" % (lane(up), lane(rb))
num = lambda v: "-" if v is None else "%.2f" % v
print("\t".join([name, level, n, num(o["f1"]), num(o["precision"]), num(o["recall"]),
                 per, "%d / %d" % (fr["count"], fr["unchanged_elements"]),
                 str(s["false_other_changes"] if isinstance(s["false_other_changes"], int)
                     else len(s["false_other_changes"])),
                 str(summ["not_verified"]), "%.1f" % float(secs), q]))
PY
  done
}

if [[ -z ${SKIP_WORLDS:-} ]]; then
  world "procedural seed 42, one route" lsm "$OLD" "--seed 42 --routes 1" "${EIGHT[*]}"
  world "procedural seed 7, grid 4, one route" lsm "$OLD" \
    "--seed 7 --world-grid-size 4 --routes 1 --route-length 2500" "${EIGHT[*]}"
  world "procedural seed 42, 4 routes" lsm "$OLD" "--seed 42 --routes 4" "${EIGHT[*]}"
  if [[ -f $maps/lanelet2_karlsruhe_mapping_example.osm ]]; then
    world "Karlsruhe (Lanelet2)" lsm "$OLD" \
      "--map $maps/lanelet2_karlsruhe_mapping_example.osm --routes 1 --route-length 800" \
      "--change-restriped 2 --change-retyped 2 --change-seed 3"
  fi
  if [[ -f $maps/MONAEast.xodr ]]; then
    world "MONAEast (OpenDRIVE)" lsm "$OLD" "--map $maps/MONAEast.xodr --routes 1 --route-length 800" \
      "--change-added 4 --change-restriped 4 --change-retyped 4 --change-seed 3"
  fi
  [[ -n ${SKIP_FRAMES:-} ]] ||
    world "procedural seed 42, one route" frames 20 "--seed 42 --routes 1 --route-length 1200" \
    "--change-removed 4 --change-added 4 --change-moved 4 --change-restriped 4 --change-retyped 4 --change-seed 3"
fi

# Cost: maps of growing road length (one route, 20 traversals), 5 new drives of 2 km on the same
# world; the update (georef + update) against a full rebuild (the chain over all 25 drives).
for size in $SIZES; do
  c=$work/cost-$size
  rm -rf "$c" && mkdir -p "$c"
  echo "bench_update: cost, $size m" >&2
  grid=$((size / 1500 + 4))
  "$bin/simulate" -q --seed 11 --world-grid-size "$grid" --routes 1 --route-length "$size" \
    --route-outward 1 --traversals 20 -o "$c/old" > /dev/null
  "$bin/simulate" -q --seed 11 --world-grid-size "$grid" --routes 1 --route-length 2000 \
    --route-outward 1 --traversals 25 -o "$c/newsim" > /dev/null
  mkdir -p "$c/new" "$c/all"
  for i in 20 21 22 23 24; do cp "$c/newsim/lsm/"*"_trav0$i".lsm.* "$c/new/"; done
  cp "$c/old/lsm/"* "$c/new/"* "$c/all/"
  origin=$(origin_of "$c/old")
  make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$c/old/lsm" WORK="$c/crowd" \
    ORIGIN="$origin" map > "$c/crowd.log" 2>&1
  t0=$(date +%s.%N)
  make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" UPDATE_MAP="$c/crowd/aggregate/map.json" \
    LSM_DIR="$c/new" WORK="$c/upd" > "$c/upd.log" 2>&1
  t1=$(date +%s.%N)
  make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$c/all" WORK="$c/rebuild" \
    ORIGIN="$origin" map > "$c/rebuild.log" 2>&1
  t2=$(date +%s.%N)
  python3 - "$size" "$c" "$(echo "$t1 - $t0" | bc)" "$(echo "$t2 - $t1" | bc)" >> "$cost" <<'PY'
import json, sys
size, c, upd, reb = sys.argv[1:]
m = json.load(open(f"{c}/crowd/aggregate/aggregate.summary.json"))
u = json.load(open(f"{c}/upd/update/update.summary.json"))
print("\t".join(["%.1f" % (int(size) / 1000), str(m["instances"]), str(u["elements_in_view"]),
                 "%.1f" % float(upd), "%.1f" % float(reb), "%.3f" % (float(upd) / float(reb))]))
PY
done

# ---- the document ----
python3 - "$rows" "$cost" "$doc" "$started" "$load" "$OLD" "$NS" "$work/f1.png" <<'PY'
import sys, subprocess, collections
rows_f, cost_f, doc, started, load, old, ns, png = sys.argv[1:]
rows = [l.rstrip("\n").split("\t") for l in open(rows_f) if l.strip()]
cost = [l.rstrip("\n").split("\t") for l in open(cost_f) if l.strip()]
out = ["<!-- update-bench begin (scripts/bench/bench_update.sh) -->",
       "## Change detection against new traversals, and the cost of an update (issue 34)", "",
       f"- date: {started}; load before: {load}",
       "- machine: 2 cores, AMD EPYC (this project's Debian 12 machine)",
       f"- command: `scripts/bench/bench_update.sh BIN_DIR` (OLD={old}, NS=\"{ns}\"): per world "
       "OLD traversals -> map (crowd.mk, truth frame); the same world with true changes "
       "(`simulate --change-*`, within change_route_distance of the routes), its traversals "
       "OLD.. as the new drives; `make -f crowd.mk UPDATE_MAP=map.json LSM_DIR=new` (georef "
       "in the map's frame + update); `evaluate changes` after renaming the report's ids to "
       "the truth's (scripts/changes-to-truth-ids.py).",
       "- columns: F1 / precision / recall over all changes; F1 per kind (removed / added / "
       "moved / restriped / retyped; - where the world has none); false removals of unchanged "
       "elements; other false changes of unchanged elements; map elements no new drive had in "
       "view (not verified); seconds of the update (georef + update, make); at N = "
       "NREBUILD the updated map against the after truth beside a full rebuild from every "
       "traversal of the after world (lane relative precision m / lowest completeness of any "
       "class / largest redundancy).", "",
       ]


def table(header, align, body):
    return (["| " + " | ".join(header) + " |", "|" + "|".join(align) + "|"] +
            ["| " + " | ".join(r) + " |" for r in body])


out += table(["world", "level", "new traversals", "F1", "precision", "recall", "F1 per kind",
              "false removals", "other false changes", "not verified", "update s",
              "updated map vs rebuild"],
             ["---", "---", "---:", "---:", "---:", "---:", "---", "---", "---:", "---:", "---:",
              "---"], rows)
out += ["", "Cost: one route of the given road length, 20 traversals -> map; 5 new drives of "
        "2 km on the same world (`--route-length 2000`); the update (georef + update, make) "
        "against a full rebuild (crowd.mk map over all 25 drives).", ""]
out += table(["road km", "map elements", "elements in the new drives' view", "update s",
              "rebuild s", "update / rebuild"], ["---:"] * 6, cost)
# F1 against N per world and level
series = collections.OrderedDict()
for r in rows:
    if r[2] != "-" and r[3] != "-":
        series.setdefault(f"{r[0]} ({r[1]})", []).append((int(r[2]), float(r[3])))
dat = png + ".dat"
with open(dat, "w") as f:
    for name, pts in series.items():
        for n, v in pts:
            f.write(f"{n} {v}\n")
        f.write("\n\n")
plots = ", ".join(f"'{dat}' index {i} using 1:2 with linespoints lw 2 pt 7 title '{name}'"
                  for i, name in enumerate(series))
if plots:
    script = f"""set terminal pngcairo size 900,560 font ',10'
set output '{png}'
set title 'Map update: change-detection F1 against new traversals'
set xlabel 'new traversals'
set ylabel 'F1 over all changes'
set logscale x
set xrange [0.8:30]
set yrange [0:1]
set grid
set key bottom right
set arrow from graph 0, first 0.8805 to graph 1, first 0.8805 nohead dt 2
set label 'dashed: anchor, one drive 0.8805 (GND map, J. Adv. Transport. 2022)' at graph 0.02, graph 0.06
plot {plots}
"""
    try:
        subprocess.run(["gnuplot"], input=script, text=True, check=True)
        out += ["", "![F1 against new traversals](images/performance-update-f1.png)"]
    except (OSError, subprocess.CalledProcessError) as e:
        out += ["", f"(no picture: gnuplot failed: {e})"]
out.append("<!-- update-bench end -->")
block = "\n".join(out) + "\n"
try:
    text = open(doc).read()
except FileNotFoundError:
    text = "# Performance: map update (issue 34)\n\n"
b, e = "<!-- update-bench begin", "<!-- update-bench end -->"
if b in text and e in text:
    text = text[:text.index(b)] + block + text[text.index(e) + len(e) + 1:]
else:
    text = text.rstrip("\n") + "\n\n" + block
open(doc, "w").write(text)
PY
[[ -f $work/f1.png ]] && cp "$work/f1.png" "$root/docs/images/performance-update-f1.png"
echo "bench_update: wrote $doc" >&2
