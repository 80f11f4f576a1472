// SemanticKITTI label files (labels/<frame>.label), read by evaluate voxels and the classifier
// training; written by lidar-semantic-map.
#include "fuzz_support.hpp"
#include "mapfuse/io/semantic_kitti.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes = fuzz::bytesOf(data, size);
  std::vector<uint32_t> labels;
  if (!fuzz::accepts([&] { labels = io::parseSemanticKittiLabels(bytes, "scan.label"); })) return 0;
  MAPFUSE_FUZZ_CHECK(labels.size() * 4 == bytes.size());
  return 0;
}
