#pragma once
/// @file The properties of a labelled-cloud format (PCD, PLY: lidar-semantic-map's map files):
/// what the parser accepts holds LiDAR class ids only, and written and read back it is the same
/// cloud.
#include <cstdint>
#include <filesystem>
#include <string>

#include "fuzz_support.hpp"
#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/labeled_cloud.hpp"

namespace mapfuse::fuzz {

/// @brief One fuzz input through `parse`, then `write` and `read` of a file named `file`.
/// @return 0 (libFuzzer's "keep going"); a finding aborts.
template <class Parse, class Write, class Read>
int cloudRoundTrip(const uint8_t* data, std::size_t size, const char* file, Parse parse,
                   Write write, Read read) {
  LabeledCloud c;
  if (!accepts([&] { c = parse(bytesOf(data, size), file); })) return 0;
  for (uint8_t l : c.labels) MAPFUSE_FUZZ_CHECK(l < kNumLidarClasses);
  const std::filesystem::path path = scratchDir() / file;
  write(path, c);
  const LabeledCloud back = read(path);
  MAPFUSE_FUZZ_CHECK(back.points == c.points && back.labels == c.labels &&
                     back.confidence == c.confidence);
  return 0;
}

}  // namespace mapfuse::fuzz
