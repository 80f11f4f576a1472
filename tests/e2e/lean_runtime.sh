#!/usr/bin/env bash
# The tools linked with static C++/OpenMP/Fortran runtimes (cmake/MapfuseLeanRuntime.cmake) must
# load no shared libstdc++ (a second copy of the C++ runtime next to the static one would break
# exceptions and iostreams), must not be position independent, and must still run: --help and a
# thrown-and-caught error (exit code 3 on a missing input) through the static runtime.
set -euo pipefail
bin="$MAPFUSE_BIN_DIR"
tools=${MAPFUSE_LEAN_TOOLS//,/ }
if [ -z "$tools" ]; then
  echo "lean_runtime: MAPFUSE_LEAN_RUNTIME off or runtimes' archives missing: nothing to check"
  exit 77
fi
for t in $tools; do
  libs=$(ldd "$bin/$t")
  if grep -Eq 'libstdc\+\+|libgomp|libgfortran' <<< "$libs"; then
    echo "lean_runtime: $t loads a shared runtime:" >&2; echo "$libs" >&2; exit 1
  fi
  file -L "$bin/$t" 2>/dev/null | grep -q "pie executable" && { echo "lean_runtime: $t is PIE" >&2; exit 1; }
  "$bin/$t" --help > /dev/null
  rc=0; "$bin/$t" /nonexistent/input.lsm.cbor -o "$(mktemp -d)/out" > /dev/null 2>&1 || rc=$?
  [ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] || { echo "lean_runtime: $t on a missing input: exit $rc" >&2; exit 1; }
done
echo "lean_runtime: ok ($tools)"
