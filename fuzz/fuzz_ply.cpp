// Binary PLY clouds (lidar-semantic-map's map.ply, read by evaluate voxels): read, written,
// read back.
#include "fuzz_cloud.hpp"
#include "mapfuse/io/ply.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  return fuzz::cloudRoundTrip(data, size, "map.ply", io::parsePly, io::writePly, io::readPly);
}
