#!/usr/bin/env bash
# Can this machine build the sanitizer pass? Compiles and runs a one-line libFuzzer target with
# clang++ -fsanitize=fuzzer,address,undefined and OpenMP (what fuzz/Sanitizers.cmake and the
# library need). Exit 0 when it can; 1 with the reason on stderr when it cannot.
set -uo pipefail
cxx=${CXX_SANITIZE:-clang++}
if ! command -v "$cxx" >/dev/null; then
  echo "check-toolchain: $cxx not found (Debian 12: apt-get install clang libclang-rt-14-dev" \
       "libomp-dev llvm, as scripts/install-deps.sh does)" >&2
  exit 1
fi
dir=$(mktemp -d "${TMPDIR:-/tmp}/mapfuse-toolchain-XXXXXX")
trap 'rm -rf "$dir"' EXIT
cat > "$dir/t.cpp" <<'CPP'
#include <cstddef>
#include <cstdint>
#include <omp.h>
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  return size > 0 && data[0] == 1 ? omp_get_max_threads() * 0 : 0;
}
CPP
if ! "$cxx" -fsanitize=fuzzer,address,undefined -fopenmp=libomp "$dir/t.cpp" -o "$dir/t" \
     2> "$dir/err.txt"; then
  echo "check-toolchain: $cxx cannot build a libFuzzer target with ASan + UBSan + OpenMP:" >&2
  head -5 "$dir/err.txt" >&2
  exit 1
fi
if ! "$dir/t" -runs=10 >/dev/null 2>&1; then
  echo "check-toolchain: a libFuzzer target built by $cxx does not run" >&2
  exit 1
fi
exit 0
