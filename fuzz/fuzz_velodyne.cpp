// KITTI Velodyne scans (velodyne_points/data/<frame>.bin): read, written, read back.
#include "fuzz_support.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/velodyne.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes = fuzz::bytesOf(data, size);
  io::VelodyneScan scan;
  if (!fuzz::accepts([&] { scan = io::parseVelodyneBin(bytes, "scan.bin"); })) return 0;
  MAPFUSE_FUZZ_CHECK(scan.size() * 16 == bytes.size());
  for (const auto& p : scan.points)
    MAPFUSE_FUZZ_CHECK(p.cwiseAbs().maxCoeff() <= float(io::bounds::kMaxLidarRange));
  return 0;
}
