#pragma once
/// @file What the binary labelled-cloud writers (pcd.cpp, ply.cpp) share: the array sizes
/// checked, the format's text header, then one fixed-size record per point, written atomically.
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/labeled_cloud.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {

/// @brief Writes `header`, then `cloud.size()` records of `stride` bytes, to `path` atomically;
/// `fill(i, record)` writes point i's bytes into its record (zeroed before).
/// @throws InputError when the points, labels and confidence differ in size; IoError when the
/// file cannot be written.
template <class Fill>
void writeCloudRecords(const std::filesystem::path& path, const LabeledCloud& cloud,
                       const std::string& header, std::size_t stride, Fill fill) {
  if (cloud.labels.size() != cloud.size() || cloud.confidence.size() != cloud.size())
    throw InputError(path.string() + ": points, labels and confidence differ in size");
  std::string body(cloud.size() * stride, '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) fill(i, body.data() + i * stride);
  writeFileAtomic(path, [&](std::ostream& out) {
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(body.data(), static_cast<std::streamsize>(body.size()));
  });
}

}  // namespace mapfuse::io
