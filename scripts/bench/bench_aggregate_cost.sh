#!/usr/bin/env bash
# Aggregate's cost on the 2 km x 100 traversals batch of bench_chain_scale (issue 18): the chain
# (make -j2 -f scripts/crowd.mk ... map) makes the aligned LSMs once, then aggregate alone is
# timed RUNS times (median wall seconds, load average beside) and (CALLGRIND=1, the default)
# its instruction count is measured once under callgrind on one thread (a figure that does not
# depend on the load), with the share of the functions named in FUNCS. Writes
# docs/performance-aggregate-cost.md.
# usage: scripts/bench/bench_aggregate_cost.sh [BIN_DIR=build/bin] [WORK=/tmp/aggregate-cost]
# env: RUNS=3, CALLGRIND=1|0, REUSE=1 keeps WORK's aligned LSMs (the same input for a before /
# after comparison of two builds), KM=2, TRAVERSALS=100
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
work=${2:-/tmp/aggregate-cost}
runs=${RUNS:-3} km=${KM:-2} trav=${TRAVERSALS:-100}
funcs=${FUNCS:-"piecesCross intersectionArea planLanelets addConnectors writeMapPng encodePng"}
mkdir -p "$work"
if [[ ${REUSE:-0} != 1 || ! -f $work/chain/align/align.summary.json ]]; then
  rm -rf "$work/sim" "$work/chain"
  "$bin/simulate" -q --traversals "$trav" --routes 1 --route-length "${km}000" \
    --world-grid-size 3 -o "$work/sim" > /dev/null
  make -s -j2 -f "$root/scripts/crowd.mk" BIN="$bin" LSM_DIR="$work/sim/lsm" WORK="$work/chain" \
    TRUTH="$work/sim/truth/vector_map.json" TRUTH_TRAJ="$work/sim/truth" map > /dev/null
fi
inputs=("$work"/chain/align/*.lsm.cbor)
doc="$root/docs/performance-aggregate-cost.md"
lines=()
times=()
for ((r = 0; r < runs; r++)); do
  load=$(cut -d' ' -f1 /proc/loadavg)
  t0=$(date +%s.%N)
  "$bin/aggregate" -q -o "$work/agg" "${inputs[@]}" > /dev/null
  t1=$(date +%s.%N)
  times+=("$(python3 -c "print(f'{$t1 - $t0:.2f}')") (load $load)")
done
median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n "$(((runs + 1) / 2))p")
lines+=("- aggregate wall seconds (${runs} runs, load average beside): ${times[*]}; median ${median}")
if [[ ${CALLGRIND:-1} == 1 ]]; then
  OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$work/callgrind.out" \
    "$bin/aggregate" -q -o "$work/agg-cg" "${inputs[@]}" > /dev/null 2> "$work/callgrind.log"
  total=$(sed -n 's/.*refs: *//p' "$work/callgrind.log" | tr -d ,)
  lines+=("- instructions (callgrind, OMP_NUM_THREADS=1): $total")
  callgrind_annotate --inclusive=yes "$work/callgrind.out" 2> /dev/null > "$work/callgrind.txt"
  for f in $funcs; do
    n=$(grep -m1 "::$f\b\|[: ]$f(" "$work/callgrind.txt" | awk '{print $1}' | tr -d , || true)
    lines+=("  - $f (inclusive): ${n:-0} ($(python3 -c "print(f'{100 * ${n:-0} / $total:.1f}')") %)")
  done
fi
{
  echo "# Performance: aggregate on the 2 km x 100 traversals batch"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "- machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p')"
  echo "- command: \`scripts/bench/bench_aggregate_cost.sh BIN_DIR WORK\`: \`simulate --traversals"
  echo "  $trav --routes 1 --route-length ${km}000 --world-grid-size 3\`, \`make -j2 -f scripts/crowd.mk ..."
  echo "  map\` (the aligned LSMs), then \`aggregate -o OUT align/*.lsm.cbor\` alone (${#inputs[@]} LSMs)"
  echo
  printf '%s\n' "${lines[@]}"
} > "$doc"
printf '%s\n' "${lines[@]}" | sed 's/^/bench_aggregate_cost: /'
echo "bench_aggregate_cost: wrote $doc"
