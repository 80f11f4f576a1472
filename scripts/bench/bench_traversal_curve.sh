#!/usr/bin/env bash
# Fig. 9 of Song et al. 2023: map quality against the number of traversals. One procedural world,
# one ~2 km route, simulated once with 100 traversals; the chain (scripts/crowd.mk: georef,
# align, aggregate) runs on the first 10, 20, 50 and 100 of them (traversal i's errors derive
# from (seed, i) alone, so the 10 are the first 10 of the 20 and so on: checked below against a
# separate 10-traversal simulation), then one `evaluate map` over the four maps.
# -> docs/performance-traversals.md, docs/performance-traversals.csv,
#    docs/images/traversal-curve.png
# usage: scripts/bench/bench_traversal_curve.sh [BIN_DIR=<root>/build/bin]   (about 5 minutes)
set -euo pipefail
source "$(dirname "$0")/lib.sh" "$@"  # root, bin, tmp (removed on exit), load
counts=(10 20 50 100)
world=(--routes 1 --route-length 2000 --world-grid-size 3 --seed 42)

nice -n 10 "$bin/simulate" -q --traversals 100 "${world[@]}" -o "$tmp/sim" > /dev/null
# subsets: traversal index < N (file names end in _trav<index>)
subset() {
  local n=$1 dir=$2
  mkdir -p "$dir"
  for f in "$tmp"/sim/lsm/*; do
    local i
    i=$(basename "$f" | sed -E 's/.*_trav0*([0-9]+).*/\1/')
    if [[ $i -lt $n ]]; then ln -s "$f" "$dir/"; fi
  done
}
# the prefix property: a 10-traversal simulation gives the same bytes as the first 10 of 100
nice -n 10 "$bin/simulate" -q --traversals 10 "${world[@]}" -o "$tmp/sim10" > /dev/null
subset 10 "$tmp/check10"
for f in "$tmp"/sim10/lsm/*; do
  cmp -s "$f" "$tmp/check10/$(basename "$f")" || {
    echo "bench_traversal_curve: $(basename "$f") differs between 10 and 100 traversals" >&2
    exit 1
  }
done

maps=()
: > "$tmp/seconds"
for n in "${counts[@]}"; do
  subset "$n" "$tmp/lsm$n"
  t0=$(date +%s.%N)
  nice -n 10 make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$tmp/lsm$n" \
    WORK="$tmp/work$n" map > /dev/null
  t1=$(date +%s.%N)
  echo "$n $(awk "BEGIN { print $t1 - $t0 }") $(ls "$tmp/lsm$n" | wc -l)" >> "$tmp/seconds"
  maps+=("$tmp/work$n/aggregate/map.cbor")
  echo "bench_traversal_curve: $n traversals done" >&2
done
nice -n 10 "$bin/evaluate" map -q --map "${maps[@]}" --traversals "${counts[@]}" \
  --truth "$tmp/sim/truth/vector_map.json" --truth-trajectories "$tmp/sim/truth" \
  -o "$tmp/eval" > /dev/null
mkdir -p "$root/docs/images"
cp "$tmp/eval/error_vs_traversals.png" "$root/docs/images/traversal-curve.png"

python3 - "$tmp" "$root/docs" "$load" "${world[*]}" <<'PY'
import csv, datetime, json, os, subprocess, sys
tmp, docs, load, world = sys.argv[1:]
cpu = subprocess.run("lscpu | sed -n 's/^Model name: *//p'", shell=True, capture_output=True,
                     text=True).stdout.strip()
ev = json.load(open(f"{tmp}/eval/evaluate.summary.json"))
secs = {int(l.split()[0]): (float(l.split()[1]), int(l.split()[2]))
        for l in open(f"{tmp}/seconds")}
rows = []
for m in ev["maps"]:
    for c in m["classes"]:
        rows.append({"traversals": m["traversals"], "class": c["class"],
                     "relative_precision_m": c.get("relative_precision_m"),
                     "completeness": c.get("completeness"), "redundancy": c.get("redundancy"),
                     "absolute_error_mean_m": (c.get("absolute_error") or {}).get("mean"),
                     "truth_count": c.get("truth_count"), "map_count": c.get("map_count")})
with open(f"{docs}/performance-traversals.csv", "w", newline="") as fh:
    w = csv.DictWriter(fh, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
classes = list(dict.fromkeys(r["class"] for r in rows))
counts = sorted(secs)
f = lambda v: "–" if v is None else f"{v:.3f}"
def table(key, title):
    out = [f"| {title} | " + " | ".join(classes) + " |", "|---|" + "---|" * len(classes)]
    for n in counts:
        by = {r["class"]: r for r in rows if r["traversals"] == n}
        out.append(f"| {n} | " + " | ".join(f(by.get(c, {}).get(key)) for c in classes) + " |")
    return out
out = f"{docs}/performance-traversals.md"
L = ["# Fig. 9: map quality against the number of traversals", "",
     f"Produced by `scripts/bench/bench_traversal_curve.sh` on {datetime.date.today()}; machine:"
     f" 2 cores, {cpu}, load average at start {load}.", "",
     f"- input: `simulate --traversals 100 {world}` (procedural world, one route of ~2 km driven"
     " 100 times); the chain (`make -f scripts/crowd.mk map`: georef, align gba_sgicp, aggregate"
     " with the defaults) on traversals 0..N-1 for N = 10, 20, 50, 100. Traversal i's errors"
     " derive from (seed, i) alone: the script checks that a 10-traversal simulation gives"
     " byte-identical LSMs to the first 10 of the 100, so each set contains the smaller ones.",
     "- scores: one `evaluate map --map m10 m20 m50 m100 --traversals 10 20 50 100 --truth"
     " truth/vector_map.json --truth-trajectories truth/` (truth clipped to what the 100 drives"
     " of the one route saw; the smaller sets drive the same route). Relative precision in m"
     " (lower is better), completeness as a share of the truth (by length for lane lines, by"
     " count otherwise).",
     "- plot: `docs/images/traversal-curve.png` (evaluate's `error_vs_traversals.png`), data:"
     " `docs/performance-traversals.csv`.", "",
     "![relative precision and completeness against traversals](images/traversal-curve.png)", "",
     "Relative precision (m):", ""] + table("relative_precision_m", "traversals") + \
    ["", "Completeness:", ""] + table("completeness", "traversals") + \
    ["", "Chain wall time (make map, -j2, under `nice -n 10` on the shared machine):", "",
     "| traversals | drives | seconds |", "|---|---|---|"] + \
    [f"| {n} | {secs[n][1]} | {secs[n][0]:.1f} |" for n in counts] + ["", "<!-- fig9 notes -->"]
old = open(out).read() if os.path.exists(out) else ""
notes = old[old.index("<!-- fig9 notes -->") + len("<!-- fig9 notes -->"):] \
    if "<!-- fig9 notes -->" in old else "\n"
open(out, "w").write("\n".join(L) + notes)
print(f"bench_traversal_curve: wrote {out}", file=sys.stderr)
PY
