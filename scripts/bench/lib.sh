# Sourced by the bench scripts, after `set -euo pipefail`, with the script's arguments:
#   source "$(dirname "$0")/lib.sh" "$@"
# Sets root (the checkout), bin (the tools: the first argument, default <root>/build/bin, made
# absolute), tmp (a scratch folder removed on exit) and load (the 1/5/15-minute load average,
# recorded next to every timing).
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
load=$(cut -d' ' -f1-3 /proc/loadavg)
