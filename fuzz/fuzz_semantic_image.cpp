// Per-frame semantics (semantics_02/<frame>.prob or .png, docs/lidar.md "Semantics format"),
// PNG when the input starts with the PNG signature byte; the PNG decoder is the one lsm-build's
// masks go through. Accepted images are written and read back.
#include "fuzz_support.hpp"
#include "mapfuse/core/classes.hpp"
#include "mapfuse/io/semantic_image.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes = fuzz::bytesOf(data, size);
  const bool png = size > 0 && data[0] == 0x89;
  const std::string name = png ? "frame.png" : "frame.prob";
  io::SemanticImage img;
  if (!fuzz::accepts([&] { img = io::parseSemanticImage(bytes, name); })) return 0;
  const std::size_t per_pixel = img.isLabels() ? 1 : std::size_t(img.channels);
  MAPFUSE_FUZZ_CHECK(img.data.size() == std::size_t(img.width) * img.height * per_pixel);
  if (img.isLabels())
    for (uint8_t l : img.data) MAPFUSE_FUZZ_CHECK(l < kNumLidarClasses);
  const auto path = fuzz::scratchDir() / name;
  io::writeSemanticImage(path, img);
  const io::SemanticImage back = io::readSemanticImage(path);
  MAPFUSE_FUZZ_CHECK(back.width == img.width && back.height == img.height && back.data == img.data);
  return 0;
}
