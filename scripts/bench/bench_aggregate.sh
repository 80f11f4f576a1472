#!/usr/bin/env bash
# Aggregate time and peak memory per road km at N traversals (default 50), written to
# docs/performance-aggregate.md. The LSMs get the simulator's TRUE keyframe poses ("oracle
# alignment") so that aggregate is measured alone, independent of georef/align quality.
# Usage: scripts/bench/bench_aggregate.sh [BIN_DIR] [TRAVERSALS]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
bin="${1:-$root/build/bin}"
n="${2:-50}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin/simulate" -q --traversals "$n" --format json -o "$tmp/sim" >/dev/null
python3 - "$tmp/sim" "$tmp/oracle" <<'PY'
import json, os, sys
sim, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
for f in sorted(os.listdir(os.path.join(sim, "lsm"))):
    lsm = json.load(open(os.path.join(sim, "lsm", f)))
    truth = json.load(open(os.path.join(sim, "truth", lsm["drive_id"] + ".trajectory.json")))
    poses = {p["id"]: p["pose"] for p in truth["poses"]}
    for k in lsm["keyframes"]:
        k["pose"] = poses[k["id"]]
    lsm["frame"], lsm["origin"] = "enu", truth["origin"]
    json.dump(lsm, open(os.path.join(out, f), "w"))
PY
cmd="$bin/aggregate -q -o $tmp/agg $tmp/oracle/*.lsm.json"
/usr/bin/time -v $cmd >"$tmp/size.json" 2>"$tmp/time.txt"
"$bin/evaluate" map -q --map "$tmp/agg/map.cbor" --truth "$tmp/sim/truth/vector_map.json" \
  --truth-trajectories "$tmp/sim/truth" -o "$tmp/eval" >/dev/null
wall=$(grep "Elapsed (wall clock)" "$tmp/time.txt" | awk '{print $NF}')
rss=$(grep "Maximum resident set size" "$tmp/time.txt" | awk '{print $NF}')
python3 - "$tmp" "$wall" "$rss" "$n" "$root/docs/performance-aggregate.md" <<'PY'
import json, sys, subprocess, datetime
tmp, wall, rss, n, out = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5]
parts = [float(x) for x in wall.split(":")]
secs = sum(v * 60 ** i for i, v in enumerate(reversed(parts)))
s = json.load(open(tmp + "/agg/aggregate.summary.json"))
km = s["size"]["road_km"]
model = subprocess.run("lscpu | grep 'Model name' | sed 's/.*: *//'", shell=True,
                       capture_output=True, text=True).stdout.strip()
nproc = subprocess.run(["nproc"], capture_output=True, text=True).stdout.strip()
md = open(tmp + "/eval/evaluate.md").read().split("\n", 2)[2]
with open(out, "w") as f:
    f.write(f"""# aggregate performance

Measured by `scripts/bench/bench_aggregate.sh` on {datetime.date.today()}.
Machine: {model}, `nproc` = {nproc} (shared with other jobs while measuring).
Input: `simulate --traversals {n}` (procedural world, default noise), keyframes replaced by the
true poses (oracle alignment), {s['inputs']['observations']} observations.
Command: `/usr/bin/time -v aggregate -q -o OUT LSM...`

| quantity | value |
|---|---|
| road covered | {km:.3f} km |
| wall time | {secs:.1f} s ({secs / km:.1f} s/km, {3600 * km / secs:.0f} km/h) |
| stage timings (read / aggregate / write) | {s['timings_s']['read']:.1f} / {s['timings_s']['aggregate']:.1f} / {s['timings_s']['write']:.1f} s |
| peak memory (max RSS) | {rss / 1024:.0f} MB ({rss / 1024 / km:.0f} MB/km) |
| native CBOR map | {s['size']['cbor_kb']:.1f} KB = {s['size']['kb_per_km']:.1f} KB/km (target 20) |
| lane pieces / fragments / instances | {s['lane_instantiation']['pieces']} / {s['lane_instantiation']['fragments']} / {s['classes']['lane_line']['instances']} |

Map quality of the same run (`evaluate map`, truth clipped to the camera view wedge of the true poses, docs/evaluate.md):

{md}
""")
print(open(out).read())
PY
