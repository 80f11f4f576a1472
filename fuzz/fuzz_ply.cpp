// Binary PLY clouds (lidar-semantic-map's map.ply, read by evaluate voxels): read, written,
// read back.
#include "fuzz_support.hpp"
#include "mapfuse/core/classes.hpp"
#include "mapfuse/io/ply.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  LabeledCloud c;
  if (!fuzz::accepts([&] { c = io::parsePly(fuzz::bytesOf(data, size), "map.ply"); })) return 0;
  for (uint8_t l : c.labels) MAPFUSE_FUZZ_CHECK(l < kNumLidarClasses);
  const auto path = fuzz::scratchDir() / "map.ply";
  io::writePly(path, c);
  const LabeledCloud back = io::readPly(path);
  MAPFUSE_FUZZ_CHECK(back.points == c.points && back.labels == c.labels &&
                     back.confidence == c.confidence);
  return 0;
}
