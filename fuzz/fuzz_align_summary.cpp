// align.summary.json as balance reads it (inputs and kept registrations).
#include "fuzz_support.hpp"
#include "mapfuse/io/align_registrations.hpp"
#include "mapfuse/io/document.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes = fuzz::bytesOf(data, size);
  io::AlignRegistrations r;
  if (!fuzz::accepts([&] {
        r = io::alignRegistrationsFromJson(
            io::parseDocument(bytes, io::Encoding::kJson, "align.summary.json"),
            "align.summary.json");
      }))
    return 0;
  for (const auto& p : r.pairs)
    MAPFUSE_FUZZ_CHECK(p.lsm_a < r.inputs.size() && p.lsm_b < r.inputs.size());
  return 0;
}
