#!/usr/bin/env bash
# Assembles docs/performance.md from docs/performance-*.md (one per topic, written by the
# benchmark scripts), with the machine it was assembled on.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out="$root/docs/performance.md"
tmp=$(mktemp)
{
  echo "# Performance"
  echo
  echo "Measured by the benchmark scripts (\`make bench\` runs them all; each topic file names its"
  echo "own command, machine and date). Never by timed unit tests."
  echo
  echo "Assembled $(date -u +%Y-%m-%d) on: $(nproc) cores, $(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1), $(free -g | awk '/Mem:/{print $2}') GiB."
  for f in "$root"/docs/performance-*.md; do
    [ -f "$f" ] || continue
    echo
    # Demote the topic's headings one level.
    sed 's/^#/##/' "$f"
  done
} > "$tmp"
mv "$tmp" "$out"
echo "bench: wrote $out" >&2
