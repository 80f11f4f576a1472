#!/usr/bin/env bash
# e2e (issue 19): malformed-input cases for every tool (tests/e2e/malformed_inputs.py): the exit
# code of docs/cli.md's table, a message naming the file and the field or key, and the earlier
# output set unchanged.
set -euo pipefail
BIN="${MAPFUSE_BIN_DIR:?}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
python3 "$(dirname "$0")/malformed_inputs.py" "$BIN" "$TMP"
