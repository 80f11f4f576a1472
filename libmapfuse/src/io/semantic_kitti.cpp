#include "mapfuse/io/semantic_kitti.hpp"

#include <cstring>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {

std::vector<uint32_t> readSemanticKittiLabels(const std::filesystem::path& path) {
  return parseSemanticKittiLabels(readBytes(path), path.string());
}

std::vector<uint32_t> parseSemanticKittiLabels(const std::string& bytes, const std::string& file) {
  if (bytes.size() % 4 != 0)
    throw ParseError(file, "size",
                     std::to_string(bytes.size()) + " bytes is not a multiple of 4 (uint32)");
  std::vector<uint32_t> out(bytes.size() / 4);
  if (!out.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());  // data() may be null
  return out;
}

void writeSemanticKittiLabels(const std::filesystem::path& path,
                              const std::vector<uint32_t>& labels) {
  std::string bytes(labels.size() * 4, '\0');
  if (!labels.empty()) std::memcpy(bytes.data(), labels.data(), bytes.size());
  writeBytesAtomic(path, bytes);
}

}  // namespace mapfuse::io
