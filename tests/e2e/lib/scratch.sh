# Sourced by the e2e scripts, after `set -euo pipefail`: sets BIN (the tools, MAPFUSE_BIN_DIR)
# and TMP, a scratch folder removed on exit, which becomes the working folder.
BIN="${MAPFUSE_BIN_DIR:?}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
cd "$TMP"
