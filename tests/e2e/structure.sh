#!/usr/bin/env bash
# e2e (issue 23): the structural rules of docs/design.md hold on the source tree (layers one way,
# thin stages and tools, parameters declared once); scripts/check-structure.py, with the files
# still being converted listed in scripts/structure-pending.txt.
set -euo pipefail
python3 "$(cd "$(dirname "$0")/../.." && pwd)/scripts/check-structure.py"
