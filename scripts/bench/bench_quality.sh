#!/usr/bin/env bash
# Map quality of the whole crowd chain (issue 5 acceptance): simulate N traversals (default 50,
# procedural world, default noise), then georef -> align gba_sgicp -> aggregate -> evaluate
# through scripts/crowd.mk; writes the evaluate table to docs/performance-quality.md.
# Then the first 5, 10 and 20 traversals of the same drives (align + aggregate from the same
# georef output) and one `evaluate map` over the four maps: error versus traversals.
# Usage: scripts/bench/bench_quality.sh [BIN_DIR] [TRAVERSALS]   (about 2 minutes at 50)
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"  # root, bin, tmp (removed on exit), load
n="${2:-50}"
"$bin/simulate" -q --traversals "$n" -o "$tmp/sim" >/dev/null
t0=$(date +%s.%N)
make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$tmp/sim/lsm" WORK="$tmp/work" \
  TRUTH="$tmp/sim/truth/vector_map.json" TRUTH_TRAJ="$tmp/sim/truth" >/dev/null
t1=$(date +%s.%N)
# the stricter reading: lane samples within 0.5 m
"$bin/evaluate" map -q --map "$tmp/work/aggregate/map.cbor" --truth "$tmp/sim/truth/vector_map.json" \
  --truth-trajectories "$tmp/sim/truth" --line-tolerance 0.5 -o "$tmp/strict" >/dev/null
# error versus traversals: subsets trav000..trav(k-1) of the same georeferenced drives
maps=() counts=()
for k in 5 10 20; do
  [[ $k -lt $n ]] || continue
  sel=()
  for f in "$tmp"/work/georef/*/*.lsm.cbor; do
    t=$(basename "$f" | sed 's/.*_trav\([0-9]*\)\..*/\1/')
    if (( 10#$t < k )); then sel+=("$f"); fi
  done
  "$bin/align" -q -o "$tmp/sub$k/align" "${sel[@]}" >/dev/null
  "$bin/aggregate" -q -o "$tmp/sub$k/aggregate" "$tmp/sub$k"/align/*.lsm.cbor >/dev/null
  maps+=("$tmp/sub$k/aggregate/map.cbor") counts+=("$k")
done
"$bin/evaluate" map -q --map "${maps[@]}" "$tmp/work/aggregate/map.cbor" --traversals "${counts[@]}" \
  "$n" --truth "$tmp/sim/truth/vector_map.json" --truth-trajectories "$tmp/sim/truth" \
  -o "$tmp/sweep" >/dev/null
python3 - "$tmp" "$n" "$t0" "$t1" "$root/docs/performance-quality.md" <<'PY'
import json, sys, subprocess, datetime
tmp, n, t0, t1, out = sys.argv[1:]
model = subprocess.run("lscpu | sed -n 's/^Model name: *//p'", shell=True, capture_output=True,
                       text=True).stdout.strip()
align = json.load(open(f"{tmp}/work/align/align.summary.json"))
md = open(f"{tmp}/work/evaluate/evaluate.md").read().split("\n", 2)[2]
md = md.split("## Trajectories")[0].rstrip()
ev = json.load(open(f"{tmp}/work/evaluate/evaluate.summary.json"))
strict = json.load(open(f"{tmp}/strict/evaluate.summary.json"))["maps"][0]["classes"]
lane = next(c for c in strict if c["class"] == "lane_line")
agg = json.load(open(f"{tmp}/work/aggregate/aggregate.summary.json"))["lane_instantiation"]
sweep = open(f"{tmp}/sweep/evaluate.md").read()
sweep = sweep[sweep.index("## Relative precision (m) versus traversals"):].split("\n## ")[0].rstrip()
sweep = sweep.replace("## Relative precision (m) versus traversals", "## Relative precision (m) versus traversals (the same drives, first k)")
sw = json.load(open(f"{tmp}/sweep/evaluate.summary.json"))["maps"]
classes = [c["class"] for c in sw[-1]["classes"]]
rows = ["", "Absolute error mean (m) / completeness versus traversals:", "",
        "| Traversals | " + " | ".join(classes) + " |", "|---" * (len(classes) + 1) + "|"]
for m in sw:
    by = {c["class"]: c for c in m["classes"]}
    cells = []
    for k in classes:
        c = by.get(k)
        cells.append(f"{c['absolute_error']['mean']:.2f} / {c['completeness']:.2f}"
                     if c and c.get("absolute_error") and c["absolute_error"].get("count") else "–")
    rows.append(f"| {m.get('traversals', '?')} | " + " | ".join(cells) + " |")
sweep += "\n" + "\n".join(rows)
with open(out, "w") as f:
    f.write(f"""# Map quality of the whole chain

Measured by `scripts/bench/bench_quality.sh` on {datetime.date.today()} (2 cores, {model}).
Input: `simulate --traversals {n}` (procedural world, default noise); chain: `make -j2 -f
scripts/crowd.mk` (georef per drive, align gba_sgicp, aggregate, evaluate with its defaults:
lane samples match within 1.0 m, truth clipped to the camera view wedge of the true poses).
Chain time {float(t1) - float(t0):.0f} s, of which align {align['seconds']:.0f} s
(GBA {align['seconds_gba']:.0f} s).

{md}

With `--line-tolerance 0.5` (the stricter reading, docs/evaluate.md): lane-line completeness \
{lane['completeness']:.3f}, redundancy {lane['redundancy']:.3f}, absolute error mean \
{lane['absolute_error']['mean']:.3f} m.

Lane instantiation: {agg['fragments']} stage-1 fragments, {agg['links']} stage-2 links, \
{agg['branch_ends']} branch ends, {agg['dropped_short']} short instances dropped.

{sweep}
""")
PY
echo "bench_quality: wrote $root/docs/performance-quality.md" >&2
