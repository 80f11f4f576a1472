// aggregate.summary.json as evaluate reads it beside a map (the number of traversals behind the
// map, stages::traversalsOf): written into a scratch folder next to an empty map.
#include "fuzz_support.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/stages/evaluate_map.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const auto dir = fuzz::scratchDir();
  fuzz::writeFile(dir / "aggregate.summary.json", fuzz::bytesOf(data, size));
  int traversals = -1;
  if (!fuzz::accepts([&] { traversals = stages::traversalsOf(dir / "map.cbor", VectorMap{}); }))
    return 0;
  MAPFUSE_FUZZ_CHECK(traversals >= 0 && traversals <= stages::kMaxTraversals);
  return 0;
}
