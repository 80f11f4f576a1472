#pragma once
/// @file What the simulator writes from a map world must read back (issue 37: simulate never
/// writes what its own readers refuse): the truth vector map and its GeoJSON as simulate writes
/// them, read again by the vector-map reader of evaluate and info, and a traversal's LSM by the
/// LSM reader of georef and aggregate. A refusal there is a finding, not a refusal of the input.
#include <cmath>

#include "fuzz_support.hpp"
#include "mapfuse/core/lsm.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/geojson.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::fuzz {

/// @brief Writes `truth` as simulate does (truth/vector_map.json and .geojson) and reads it back.
inline void checkTruthReadsBack(const VectorMap& truth) {
  const std::filesystem::path file = scratchDir() / "vector_map.json";
  try {
    io::writeVectorMap(file, truth);
    io::writeGeoJson(scratchDir() / "vector_map.geojson", truth);
    const VectorMap back = io::readVectorMap(file);
    MAPFUSE_FUZZ_CHECK(back.instances.size() == truth.instances.size());
  } catch (const Error& e) {
    fail(std::string("the truth simulate would write is refused: ") + e.what(), __FILE__, __LINE__);
  }
}

/// @brief Writes a traversal's LSM as simulate does and reads it back.
inline void checkLsmReadsBack(const Lsm& lsm) {
  const std::filesystem::path file = scratchDir() / "drive.lsm.json";
  try {
    io::writeLsm(file, lsm);
    const Lsm back = io::readLsm(file);
    MAPFUSE_FUZZ_CHECK(back.keyframes.size() == lsm.keyframes.size());
  } catch (const Error& e) {
    fail(std::string("the LSM simulate would write is refused: ") + e.what(), __FILE__, __LINE__);
  }
}

}  // namespace mapfuse::fuzz
