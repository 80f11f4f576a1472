#!/usr/bin/env bash
# Installs mapfuse's build and test dependencies from Debian 12 packages.
# Idempotent and non-interactive; returns quickly when everything is present.
# usage: scripts/install-deps.sh [--demo]
#   --demo: only what `make demo` needs to configure, build demo_tools and run the demo (243 of the
#   604 packages a fresh Debian 12 machine installed for everything on 2026-11-29, 0.85 of
#   2.3 GB: PCL with VTK and Qt is most of the rest). `make test` installs the rest.
set -euo pipefail

# configure (CMakeLists.txt and tests/CMakeLists.txt's find_package), the library and the demo
DEMO_PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config git
  libeigen3-dev libceres-dev
  libopencv-dev
  libboost-dev libgeographiclib-dev
  libcli11-dev nlohmann-json3-dev catch2
  libpugixml-dev zlib1g-dev
)
# the tests, benchmarks, batch runners and interop checks
TEST_PACKAGES=(
  libpcl-dev
  libopenmpi-dev
  gdal-bin snakemake
  osmium-tool python3-shapely
  slurmctld slurmd slurm-client munge
  # the sanitizer build and the fuzz targets (fuzz/README.md): clang with libFuzzer and the
  # sanitizer runtimes (libclang-rt-14-dev, only recommended by clang-14), OpenMP for clang,
  # llvm-symbolizer for readable sanitizer reports
  clang libclang-rt-14-dev libomp-dev llvm
  gnuplot-nox
  # PCL's converters (23 MB beside libpcl-dev): tests/e2e/point_cloud_viewers.sh reads map.pcd
  # with pcl_pcd2ply
  pcl-tools
  # the real Lanelet2 library that tests/e2e/lanelet2_validate.sh builds from ../shared/tools/lanelet2
  # (cached outside the repository, in ~/.cache/mapfuse/lanelet2-build)
  libboost-filesystem-dev libboost-serialization-dev libboost-program-options-dev
)
PACKAGES=("${DEMO_PACKAGES[@]}")
case "${1:-}" in
  --demo) ;;
  "") PACKAGES+=("${TEST_PACKAGES[@]}") ;;
  *) echo "install-deps: unknown option '$1' (usage: install-deps.sh [--demo])" >&2; exit 2 ;;
esac

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present" >&2
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done" >&2
