// Vector maps (docs/formats.md "Vector map"), JSON when the input starts with '{', else CBOR
// (plain or compact: points_q / bezier_q): the reader of evaluate, stitch and info.
#include "fuzz_support.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/vector_map_io.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes = fuzz::bytesOf(data, size);
  const io::Encoding enc = size > 0 && data[0] == '{' ? io::Encoding::kJson : io::Encoding::kCbor;
  VectorMap map;
  if (!fuzz::accepts([&] {
        map = io::vectorMapFromJson(io::parseDocument(bytes, enc, "fuzz.map"), "fuzz.map");
      }))
    return 0;
  for (const auto& inst : map.instances) {
    for (const auto& p : inst.points)
      MAPFUSE_FUZZ_CHECK(p.cwiseAbs().maxCoeff() <= io::bounds::kMaxCoordinate + 1.0);
    MAPFUSE_FUZZ_CHECK(instanceCentre(inst).allFinite());
  }
  MAPFUSE_FUZZ_CHECK(std::isfinite(totalLineLength(map, CrowdClass::kLaneLine)));
  // Written plainly and compactly (what aggregate writes to map.cbor), it reads back.
  for (const bool compact : {false, true}) {
    io::VectorMapWriteOptions options;
    options.compact = compact;
    options.coordinate_quantum = compact ? 1.0 / 256 : 0.0;
    const std::vector<uint8_t> cbor = io::Json::to_cbor(io::vectorMapToJson(map, options));
    const VectorMap back = io::vectorMapFromJson(
        io::parseDocument(std::string(cbor.begin(), cbor.end()), io::Encoding::kCbor, "again"),
        "again");
    MAPFUSE_FUZZ_CHECK(back.instances.size() == map.instances.size());
  }
  return 0;
}
