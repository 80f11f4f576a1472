// One KITTI OXTS record (oxts/data/<frame>.txt) and the two poses made of it.
#include "fuzz_support.hpp"
#include "mapfuse/geo/oxts.hpp"
#include "mapfuse/io/oxts_line.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::string text = fuzz::bytesOf(data, size);
  const auto eol = text.find('\n');
  if (eol != std::string::npos) text.resize(eol);  // readOxts reads the first line
  geo::OxtsRecord r;
  if (!fuzz::accepts([&] { r = io::parseOxtsLine(text, "oxts.txt"); })) return 0;
  MAPFUSE_FUZZ_CHECK(geo::oxtsToMercatorPose(r, geo::mercatorScale(r.lat)).matrix().allFinite());
  const geo::EnuConverter enu({r.lat, r.lon, 0.0});
  MAPFUSE_FUZZ_CHECK(geo::oxtsToEnuPose(r, enu).matrix().allFinite());
  return 0;
}
