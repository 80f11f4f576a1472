#!/usr/bin/env bash
# docs/cli-reference.md must match what the tools print for --help.
set -euo pipefail
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
bash "$MAPFUSE_SOURCE_DIR/scripts/gen-cli-docs.sh" "$MAPFUSE_BIN_DIR" "$tmp" 2>/dev/null
if ! diff -u "$MAPFUSE_SOURCE_DIR/docs/cli-reference.md" "$tmp"; then
  echo "docs/cli-reference.md is out of date: run scripts/gen-cli-docs.sh build/bin" >&2
  exit 1
fi
# Every tool answers --help with exit 0 and lists its options.
for dir in "$MAPFUSE_SOURCE_DIR"/apps/*/; do
  tool=$(basename "$dir")
  [ -f "$dir/main.cpp" ] || continue
  # grep reads to the end: -q would close the pipe early and pipefail would see SIGPIPE
  "$MAPFUSE_BIN_DIR/$tool" --help | grep -- "--help" >/dev/null
done
echo "cli_docs: ok"
