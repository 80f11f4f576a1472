// KITTI timestamps files (velodyne_points/timestamps*.txt).
#include <cmath>

#include "fuzz_support.hpp"
#include "mapfuse/io/kitti_raw.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::vector<double> stamps;
  if (!fuzz::accepts(
          [&] { stamps = io::parseKittiTimestamps(fuzz::bytesOf(data, size), "timestamps.txt"); }))
    return 0;
  for (double s : stamps) MAPFUSE_FUZZ_CHECK(s >= 0 && s < 86401);
  return 0;
}
