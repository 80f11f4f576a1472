// OpenDRIVE maps (docs/simulate.md "OpenDRIVE maps"): the reader and simulate's conversion of
// the map into a World (geometry, lanes, routing, road marks, signals, objects).
#include "fuzz_support.hpp"
#include "mapfuse/io/opendrive.hpp"
#include "mapfuse/sim/opendrive_world.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string xml = fuzz::bytesOf(data, size);
  io::OdrMap map;
  if (!fuzz::accepts([&] { map = io::parseOpenDrive(xml, "fuzz.xodr"); })) return 0;
  fuzz::accepts([&] { sim::worldFromOpenDrive(map, geo::GeoOrigin{48.0, 11.0, 500.0}); });
  return 0;
}
