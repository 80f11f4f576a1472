#!/usr/bin/env bash
# lsm-build's LSMs against the simulator's own LSMs of the same world, through the same chain
# (issue 6: "LSMs from lsm-build feed georef/align/aggregate and reach the aggregate issue's
# accuracy"): simulate --config samples/demo/crowd-frames.json --traversals N at --level frames
# and --level lsm, then make -j2 -f scripts/crowd.mk (FRAMES_DIR: lsm-build per drive; LSM_DIR)
# with evaluate. Writes docs/performance-frames-chain.md.
# usage: scripts/bench/bench_frames_chain.sh [BIN_DIR=build/bin] [WORK=/tmp/frames-chain]
# env: TRAVERSALS="20 50"
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
work=${2:-/tmp/frames-chain}
counts=${TRAVERSALS:-"20 50"}
mkdir -p "$work"
rows="$work/rows.md"
: > "$rows"
for n in $counts; do
  for level in lsm frames; do
    sim="$work/sim-$level-$n" out="$work/chain-$level-$n"
    rm -rf "$sim" "$out"
    "$bin/simulate" -q --config "$root/samples/demo/crowd-frames.json" --traversals "$n" \
      --level "$level" -o "$sim" > /dev/null
    if [[ $level == frames ]]; then src=(FRAMES_DIR="$sim/frames"); else src=(LSM_DIR="$sim/lsm"); fi
    make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" "${src[@]}" WORK="$out" \
      TRUTH="$sim/truth/vector_map.json" TRUTH_TRAJ="$sim/truth" > /dev/null
    python3 - "$n" "$level" "$out/evaluate/evaluate.summary.json" >> "$rows" <<'PY'
import json, sys
n, level, path = sys.argv[1:]
d = json.load(open(path))
cls = {c["class"]: c for c in d["maps"][0]["classes"]}
def cell(name):
    c = cls.get(name)
    if not c:
        return "-"
    rel = c.get("relative_precision_m")
    return f"{c['completeness']:.2f} / {c['redundancy']:.2f} / {rel:.3f}" if rel is not None else \
        f"{c['completeness']:.2f} / {c['redundancy']:.2f} / -"
who = "lsm-build" if level == "frames" else "simulator LSMs"
names = ["lane_line", "stop_line", "ground_arrow", "crosswalk", "traffic_sign", "traffic_light", "pole"]
print(f"| {n} | {who} | {d.get('trajectory_ate_rms_mean_m', 0):.2f} | " +
      " | ".join(cell(x) for x in names) + " |")
PY
    echo "bench_frames_chain: $level $n done" >&2
  done
done
# the sections bench_vp_calibration.sh and bench_frames_worlds.sh write into the same page
# survive this rewrite
doc="$root/docs/performance-frames-chain.md"
keep="$work/vp-section.md"
if [[ -f $doc ]]; then
  sed -n -e '/<!-- vp-calibration begin/,/<!-- vp-calibration end -->/p' \
    -e '/<!-- frames-worlds begin/,/<!-- frames-worlds end -->/p' "$doc" > "$keep"
else
  : > "$keep"
fi
{
  echo "# Performance: lsm-build LSMs against the simulator's LSMs, whole chain"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "- machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "- command: \`scripts/bench/bench_frames_chain.sh BIN_DIR WORK\`: \`simulate --config"
  echo "  samples/demo/crowd-frames.json --traversals N --level frames|lsm\`, then \`make -j2 -f"
  echo "  scripts/crowd.mk FRAMES_DIR=...|LSM_DIR=... TRUTH=... TRUTH_TRAJ=...\` (lsm-build per drive,"
  echo "  georef, align gba_sgicp, aggregate, evaluate with its defaults)."
  echo "- cells: completeness / redundancy / relative precision [m] per class; ATE: mean over drives"
  echo "  of the keyframe RMS position error after align [m]. Aggregate issue's targets: completeness"
  echo "  >= 0.95, redundancy <= 0.05, relative precision lane <= 0.10, arrows <= 0.30, signs <= 0.35,"
  echo "  poles <= 0.30 m."
  echo
  echo "| traversals | LSMs from | ATE | lane line | stop line | arrow | crosswalk | sign | light | pole |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  cat "$rows"
  if [[ -s $keep ]]; then echo; cat "$keep"; fi
} > "$doc"
cat "$root/docs/performance-frames-chain.md"
