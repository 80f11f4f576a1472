// LSM documents (docs/formats.md "LSM"), JSON when the input starts with '{', else CBOR: the
// reader of georef, align, aggregate, tile, balance, evaluate and info.
#include <algorithm>

#include "fuzz_support.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes = fuzz::bytesOf(data, size);
  const io::Encoding enc = size > 0 && data[0] == '{' ? io::Encoding::kJson : io::Encoding::kCbor;
  Lsm lsm;
  if (!fuzz::accepts(
          [&] { lsm = io::lsmFromJson(io::parseDocument(bytes, enc, "fuzz.lsm"), "fuzz.lsm"); }))
    return 0;
  // Accepted: within the bounds, and usable downstream (every element in its LSM frame).
  for (const auto& k : lsm.keyframes)
    MAPFUSE_FUZZ_CHECK(k.T_frame_body.translation().cwiseAbs().maxCoeff() <=
                       io::bounds::kMaxCoordinate);
  for (const auto& e : lsm.elements)
    for (const auto& p : lsm.pointsInFrame(e)) MAPFUSE_FUZZ_CHECK(p.allFinite());
  // What the writer makes of it reads back, in both encodings, with the same content.
  const io::Json written = io::lsmToJson(lsm);
  const std::vector<uint8_t> cbor = io::Json::to_cbor(written);
  for (const std::string& again : {written.dump(), std::string(cbor.begin(), cbor.end())}) {
    const io::Encoding e = again.front() == '{' ? io::Encoding::kJson : io::Encoding::kCbor;
    const Lsm back = io::lsmFromJson(io::parseDocument(again, e, "again.lsm"), "again.lsm");
    MAPFUSE_FUZZ_CHECK(back.keyframes.size() == lsm.keyframes.size());
    MAPFUSE_FUZZ_CHECK(back.elements.size() == lsm.elements.size());
    MAPFUSE_FUZZ_CHECK(back.gps.size() == lsm.gps.size());
    for (std::size_t i = 0; i < lsm.keyframes.size(); ++i)
      MAPFUSE_FUZZ_CHECK(back.keyframes[i].T_frame_body.translation() ==
                         lsm.keyframes[i].T_frame_body.translation());
    for (std::size_t i = 0; i < lsm.elements.size(); ++i)
      MAPFUSE_FUZZ_CHECK(back.elements[i].points_body == lsm.elements[i].points_body);
  }
  return 0;
}
