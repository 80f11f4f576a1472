#pragma once
/// @file The road length a set of drives covers, the denominator of the map size figure KB/km
/// (§5, Song et al. 2023: maps of ~20 KB/km): a road driven many times counts once.
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"

namespace mapfuse::aggregate {

struct RoadLengthSettings {
  double tolerance = 10.0;  ///< m, lateral width merged when measuring road km

  template <class V>
  void visit(V& v) {
    // samples are hashed on a grid of this cell: a tiny cell overflows the keys, a huge one
    // compares every sample with every other
    v("road_tolerance", tolerance, "m", "lateral width counted once when measuring road km",
      param::in(0.1, 100));
  }
};

/// @brief Road length (km) covered by the LSM trajectories: keyframe paths sampled every metre,
/// a sample counting only when no sample of an earlier drive lies within `settings.tolerance`
/// metres.
double coveredRoadKm(const std::vector<Lsm>& lsms, const RoadLengthSettings& settings);

}  // namespace mapfuse::aggregate
