#!/usr/bin/env bash
# `make bench`: runs every scripts/bench/bench_*.sh (each writes docs/performance-<topic>.md),
# then assembles docs/performance.md with the machine, the date and every topic.
# Usage: scripts/bench/run-all.sh BIN_DIR
set -uo pipefail
bin=${1:?usage: run-all.sh BIN_DIR}
root=$(cd "$(dirname "$0")/../.." && pwd)
status=0
for script in "$root"/scripts/bench/bench_*.sh; do
  [ -f "$script" ] || continue
  echo "== $(basename "$script")" >&2
  if ! bash "$script" "$bin"; then
    echo "bench: $(basename "$script") failed" >&2
    status=1
  fi
done
bash "$root/scripts/bench/assemble.sh"
exit $status
