#!/usr/bin/env bash
# Map quality of the whole crowd chain (issue 5 acceptance): simulate N traversals (default 50,
# procedural world, default noise), then georef -> align gba_sgicp -> aggregate -> evaluate
# through scripts/crowd.mk; writes the evaluate table to docs/performance-quality.md.
# Usage: scripts/bench/bench_quality.sh [BIN_DIR] [TRAVERSALS]   (about 3 minutes at 50)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
bin=$(cd "${1:-$root/build/bin}" && pwd)
n="${2:-50}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin/simulate" -q --traversals "$n" -o "$tmp/sim" >/dev/null
t0=$(date +%s.%N)
make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$tmp/sim/lsm" WORK="$tmp/work" \
  TRUTH="$tmp/sim/truth/vector_map.json" TRUTH_TRAJ="$tmp/sim/truth" >/dev/null
t1=$(date +%s.%N)
# the stricter reading: lane samples within 0.5 m
"$bin/evaluate" map -q --map "$tmp/work/aggregate/map.cbor" --truth "$tmp/sim/truth/vector_map.json" \
  --truth-trajectories "$tmp/sim/truth" --line-tolerance 0.5 -o "$tmp/strict" >/dev/null
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
with open(out, "w") as f:
    f.write(f"""# Map quality of the whole chain

Measured by `scripts/bench/bench_quality.sh` on {datetime.date.today()} (2 cores, {model}).
Input: `simulate --traversals {n}` (procedural world, default noise); chain: `make -j2 -f
scripts/crowd.mk` (georef per drive, align gba_sgicp, aggregate, evaluate with its defaults:
lane samples match within 1.0 m, truth clipped to the camera view wedge of the true poses).
Chain time {float(t1) - float(t0):.0f} s, of which align {align['seconds']:.0f} s
(GBA {align['seconds_gba']:.0f} s).

{md}

With `--line-tolerance 0.5` (the stricter reading, docs/evaluate.md): lane-line completeness
{lane['completeness']:.3f}, redundancy {lane['redundancy']:.3f}, absolute error mean
{lane['absolute_error']['mean']:.3f} m. Lane instantiation: {agg['fragments']} stage-1 fragments,
{agg['links']} stage-2 links, {agg['branch_ends']} branch ends, {agg['dropped_short']} short
instances dropped.
""")
PY
echo "bench_quality: wrote $root/docs/performance-quality.md" >&2
