// Binary PCD clouds (lidar-semantic-map's map.pcd): read, written, read back.
#include "fuzz_cloud.hpp"
#include "mapfuse/io/pcd.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  return fuzz::cloudRoundTrip(data, size, "map.pcd", io::parsePcd, io::writePcd, io::readPcd);
}
