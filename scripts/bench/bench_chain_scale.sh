#!/usr/bin/env bash
# Issue 18 acceptance: the crowd chain (make -j2 -f scripts/crowd.mk ... map, timed to the map) on
# one procedural route of L km driven by N traversals: 50 traversals at 2, 5, 10 and 20 km of
# road and 100 traversals at 2 km. Per row: chain seconds, road km/h, seconds per driven km, peak
# RSS of the largest process (GNU time over make), the load average before and after, and the
# map's evaluate figures (run afterwards, untimed). Rows are kept in docs/performance-chain-scale.jsonl
# (a rerun of some rows replaces only those), the table is written into docs/performance-chain.md
# between the "chain-scale" markers, and docs/images/performance-chain-scale.png is plotted
# (seconds and peak MB against driven km; gnuplot).
#
# usage: scripts/bench/bench_chain_scale.sh [BIN_DIR=<root>/build/bin] [ROW...]
#   ROW = KM:TRAVERSALS[:ROUTES] (default: 2:50 5:50 10:50 20:50 2:100 and the network rows
#   2:50:8 10:50:8 50:50:8 100:50:8). NICE=10 runs the chain
#   with nice. With ROUTES > 1 (issue 36, a crowd over a network, e.g. 10:50:8) the world is a
#   grid of about KM road km (3, 6, 12, 17 intersections a side for 2, 10, 50, 100 km) and each
#   of the ROUTES random routes is 2 KM / ROUTES km long (at least 1 km): every road driven by a
#   few of the traversals, in both directions, the routes crossing at junctions.
#   TILE_SIZE=<m> (optional) adds a tiled run of each row (name suffix "-tiled"); with
#   TILED_ONLY=1 only the tiled run (the untiled row already recorded stays).
# About 8 minutes on a quiet 2-core machine (2026-11-29 host), most of it the 20 km and 119 km rows.
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"  # root, bin, tmp (removed on exit), load
shift || true
rows_wanted=("$@")
[[ ${#rows_wanted[@]} -gt 0 ]] || rows_wanted=(2:50 5:50 10:50 20:50 2:100 2:50:8 10:50:8 50:50:8 100:50:8)
tile=${TILE_SIZE:-}
nice_n=${NICE:-0}
jsonl="$root/docs/performance-chain-scale.jsonl"
touch "$jsonl"

# Procedural world grid per route length: big enough that the route need not repeat itself.
grid_for() {
  case $1 in 1 | 2) echo 3 ;; 5) echo 4 ;; 10) echo 6 ;; 20) echo 9 ;; *) echo 12 ;; esac
}

# Network worlds (ROUTES > 1): grid size per road km.
network_grid_for() {
  case $1 in 1 | 2) echo 3 ;; 5) echo 4 ;; 10) echo 6 ;; 20) echo 8 ;; 50) echo 12 ;; *) echo 17 ;; esac
}

for spec in "${rows_wanted[@]}"; do
  IFS=: read -r km trav routes <<< "$spec"
  routes=${routes:-1}
  if ((routes > 1)); then
    name="network-${km}km-${trav}x${routes}"
    route_m=$((2 * km * 1000 / routes))
    ((route_m >= 1000)) || route_m=1000
    grid=$(network_grid_for "$km")
  else
    name="procedural-${km}km-${trav}"
    route_m="${km}000"
    grid=$(grid_for "$km")
  fi
  sim="$tmp/$name.sim"
  "$bin/simulate" -q --traversals "$trav" --routes "$routes" --route-length "$route_m" \
    --world-grid-size "$grid" -o "$sim" > /dev/null
  variants=("" ${tile:+$tile})
  [[ -n ${TILED_ONLY:-} && -n $tile ]] && variants=("$tile")
  for t in "${variants[@]}"; do
    work="$tmp/$name${t:+-tiled}.work"
    mk=(make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$sim/lsm" WORK="$work"
      TRUTH="$sim/truth/vector_map.json" TRUTH_TRAJ="$sim/truth" ${t:+TILE_SIZE=$t})
    load0=$(cut -d' ' -f1-3 /proc/loadavg)
    t0=$(date +%s.%N)
    /usr/bin/time -f '%M %U %S' -o "$tmp/time" nice -n "$nice_n" "${mk[@]}" map > /dev/null
    t1=$(date +%s.%N)
    load1=$(cut -d' ' -f1-3 /proc/loadavg)
    "${mk[@]}" > /dev/null  # evaluate, untimed
    python3 - "$name${t:+-tiled}" "$km" "$trav" "$t" "$sim" "$work" "$t0" "$t1" "$tmp/time" \
      "$load0" "$load1" "$nice_n" "$jsonl" "$routes" <<'PY'
import datetime, json, sys
name, km, trav, tile, sim, work, t0, t1, timef, load0, load1, nice_n, jsonl, routes = sys.argv[1:]
rss_kb, user, sys_s = open(timef).read().split()[-3:]
def summary(stage):
    return json.load(open(f"{work}/{stage}/{stage}.summary.json"))
driven = json.load(open(f"{sim}/simulate.summary.json"))["km_driven"]
size = summary("stitch" if tile else "aggregate").get("size", {})
classes = {c["class"]: c for c in summary("evaluate")["maps"][0]["classes"]}
keep = ("completeness", "redundancy", "relative_precision_m", "map_count", "truth_count",
        "completeness_observed", "truth_observed")
row = {"name": name, "route_km": float(km), "traversals": int(trav), "tile": tile or None,
       "routes": int(routes),
       "seconds": float(t1) - float(t0), "cpu_seconds": float(user) + float(sys_s),
       "rss_mb": int(rss_kb) / 1024, "road_km": size.get("road_km"), "driven_km": driven,
       "load_before": load0, "load_after": load1, "nice": int(nice_n),
       "date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
       "classes": {k: {f: v.get(f) for f in keep} for k, v in classes.items()}}
try:
    a = summary("align")
    row["align_seconds"] = {k: a.get("seconds_" + k) for k in ("registration", "pose_graph", "gba")}
    row["align_pairs"] = a.get("constraints_proposed")
    row["ties"] = a.get("ties")
except OSError:
    pass
rows = [json.loads(l) for l in open(jsonl) if l.strip()]
rows = [r for r in rows if r["name"] != name] + [row]
rows.sort(key=lambda r: (r["tile"] is not None, r.get("routes", 1), r["traversals"], r["route_km"]))
open(jsonl, "w").write("".join(json.dumps(r) + "\n" for r in rows))
print(f"bench_chain_scale: {name}: {row['seconds']:.1f} s, {row['rss_mb']:.0f} MB, load {load0}",
      file=sys.stderr)
PY
  done
done

python3 "$root/scripts/bench/chain_scale_report.py" "$jsonl" "$root/docs/performance-chain.md" \
  "$root/docs/images/performance-chain-scale.png"
