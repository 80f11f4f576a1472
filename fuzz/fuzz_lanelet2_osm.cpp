// Lanelet2 OSM maps (docs/simulate.md "Lanelet2 maps"): the reader and simulate's conversion of
// the map into a World around its first node. The truth simulate would write from an accepted
// world must read back (fuzz_world.hpp: simulate never writes what its own readers refuse).
#include "fuzz_support.hpp"
#include "fuzz_world.hpp"
#include "mapfuse/io/lanelet2_osm.hpp"
#include "mapfuse/sim/lanelet2_world.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string xml = fuzz::bytesOf(data, size);
  io::Lanelet2Map map;
  if (!fuzz::accepts([&] { map = io::parseLanelet2Osm(xml, "fuzz.osm"); })) return 0;
  if (!map.first_node) return 0;
  sim::World world;
  if (!fuzz::accepts([&] { world = sim::worldFromLanelet2(map, *map.first_node); })) return 0;
  fuzz::checkTruthReadsBack(world.truth);
  return 0;
}
