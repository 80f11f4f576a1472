#pragma once
/// @file SemanticKITTI per-scan label files: one uint32 per Velodyne point, semantic id in the
/// low 16 bits, instance id in the high 16 bits.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace mapfuse::io {

/// @brief Reads a `.label` file. @throws IoError when unreadable; ParseError(file, "size")
/// when the byte count is not a multiple of 4.
std::vector<uint32_t> readSemanticKittiLabels(const std::filesystem::path& path);
/// @brief The same from the bytes of a file; `file` names it in errors.
std::vector<uint32_t> parseSemanticKittiLabels(const std::string& bytes, const std::string& file);

/// @brief Writes a `.label` file atomically.
void writeSemanticKittiLabels(const std::filesystem::path& path,
                              const std::vector<uint32_t>& labels);

/// @brief Semantic id (low 16 bits) of a label word.
inline uint16_t semanticIdOf(uint32_t word) {
  return static_cast<uint16_t>(word & 0xffffu);
}

}  // namespace mapfuse::io
