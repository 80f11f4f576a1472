#!/usr/bin/env bash
# Runs every fuzz target (or the ones named) for a set time, seeded from the generated corpus,
# and reports per target the executions, the corpus size and any finding.
#   fuzz/run.sh FUZZ_BIN_DIR WORK_DIR SECONDS [JOBS] [TARGET...]
# WORK_DIR/seeds/<target>/ holds the seeds (fuzz/make-corpus.sh), WORK_DIR/corpus/<target>/ the
# corpus libFuzzer grows (kept between runs), WORK_DIR/artifacts/ the inputs of findings,
# WORK_DIR/logs/<target>.log each run's log and WORK_DIR/report.tsv the table. JOBS targets run
# at a time (default 1). Exit status 1 when any target found a crash, a leak, a timeout, an
# out-of-memory or a sanitizer report.
set -uo pipefail
bin=$(cd "$1" && pwd); work=$2; seconds=$3; jobs=${4:-1}; shift 4 2>/dev/null || shift $#
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"/{corpus,artifacts,logs,seeds}
work=$(cd "$work" && pwd)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in "$bin"/fuzz_*; do [ -x "$f" ] && targets+=("$(basename "$f")"); done
fi
[ ${#targets[@]} -gt 0 ] || { echo "fuzz: no fuzz targets in $bin" >&2; exit 2; }
symbolizer=$(command -v llvm-symbolizer || ls /usr/lib/llvm-*/bin/llvm-symbolizer 2>/dev/null | head -1)
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:symbolize=1${symbolizer:+:external_symbolizer_path=$symbolizer}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

# Input size limit per target: documents and text a few KB to 64 KB, binary clouds larger.
# OpenDRIVE 256 KB: real maps are large (MONAEast, 25 roads and 4 junctions of a few blocks of
# Munich, is 153 KB: RoadRunner writes every number with 17 digits), and the whole of it is a
# seed; libFuzzer's length control still starts mutants small and grows them slowly.
max_len() {
  case "$1" in
    fuzz_opendrive|fuzz_opendrive_drive) echo 262144 ;;
    fuzz_stitch|fuzz_kitti_sequence) echo 65536 ;;
    fuzz_velodyne|fuzz_semantic_labels|fuzz_ply|fuzz_pcd|fuzz_semantic_image) echo 65536 ;;
    fuzz_lanelet2_osm|fuzz_drive_frames|fuzz_lsm|fuzz_vector_map) echo 65536 ;;
    *) echo 16384 ;;
  esac
}

# Time per input before libFuzzer calls it a hang: 25 s, and 120 s for fuzz_opendrive_drive,
# whose every input is a map read, a world built, a route planned, driven at 100 Hz and observed
# (the esmini seeds take 1-4 s of CPU each under ASan, and on the shared 2-core machine a
# fuzzer at nice 10 gets a fraction of a core: a 500 m road took 37 s of wall time).
unit_timeout() {
  case "$1" in
    fuzz_opendrive_drive) echo 120 ;;
    *) echo 25 ;;
  esac
}

run_one() {
  local t=$1 dict=() corpus="$work/corpus/$1" seeds="$work/seeds/$1"
  mkdir -p "$corpus" "$seeds"
  [ -f "$here/dict/$t.dict" ] && dict=(-dict="$here/dict/$t.dict")
  (cd "$work" && nice -n 10 "$bin/$t" -max_total_time="$seconds" -timeout="$(unit_timeout "$t")" -rss_limit_mb=2560 \
     -max_len="$(max_len "$t")" -print_final_stats=1 -artifact_prefix="$work/artifacts/$t-" \
     "${dict[@]}" "$corpus" "$seeds" >"$work/logs/$t.log" 2>&1)
  local rc=$?
  local execs rss files
  execs=$(grep -m1 'stat::number_of_executed_units' "$work/logs/$t.log" | awk '{print $2}')
  rss=$(grep -m1 'stat::peak_rss_mb' "$work/logs/$t.log" | awk '{print $2}')
  files=$(find "$corpus" -type f | wc -l)
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$t" "$rc" "${execs:-?}" "$files" \
    "$(du -sk "$corpus" | cut -f1)" "${rss:-?}" > "$work/logs/$t.row"
}

start=$(date +%s)
running=0
for t in "${targets[@]}"; do
  run_one "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then wait -n; running=$((running - 1)); fi
done
wait

printf 'target\texit\texecutions\tcorpus_files\tcorpus_kb\tpeak_rss_mb\n' > "$work/report.tsv"
failed=0
for t in "${targets[@]}"; do
  cat "$work/logs/$t.row" >> "$work/report.tsv"
  if [ "$(cut -f2 "$work/logs/$t.row")" != 0 ]; then
    failed=1
    echo "fuzz: FINDING in $t (log: $work/logs/$t.log):" >&2
    grep -E 'ERROR:|runtime error|mapfuse fuzz finding|Test unit written|SUMMARY' \
      "$work/logs/$t.log" | head -8 >&2
  fi
done
awk -F'\t' '{printf "%-24s %5s %12s %13s %10s %12s\n", $1, $2, $3, $4, $5, $6}' \
  "$work/report.tsv" >&2
echo "fuzz: ${#targets[@]} targets, ${seconds} s each, $jobs at a time, $(( $(date +%s) - start )) s" >&2
exit $failed
