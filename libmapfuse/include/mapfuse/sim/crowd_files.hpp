#pragma once
/// @file The files of a crowd's traversals (docs/simulate.md "Outputs"): per traversal the true
/// trajectory (truth/<drive>.trajectory.json, mapfuse.trajectory) and, by level, its LSM
/// (lsm/<drive>.lsm.cbor|json) or its raw frames folder (frames/<drive>/). Traversals are
/// simulated in parallel; each is deterministic in its index.
#include <filesystem>
#include <string>

#include "mapfuse/geo/origin.hpp"
#include "mapfuse/sim/crowd.hpp"

namespace mapfuse::sim {

/// What to write of each traversal.
struct CrowdFiles {
  std::string level = "lsm";    ///< lsm | frames | truth
  std::string format = "cbor";  ///< LSM encoding: cbor | json
};

/// @brief Simulates traversals 0 .. settings.traversals - 1 of `crowd` and writes their files
/// below `out`; returns the summed statistics in traversal order.
/// @throws Error naming the first traversal that failed.
CrowdStats writeCrowdTraversals(const Crowd& crowd, const CrowdSettings& settings,
                                const CrowdFiles& files, const geo::GeoOrigin& origin,
                                const std::filesystem::path& out);

}  // namespace mapfuse::sim
