#pragma once
/// @file Lane-line instantiation by two-stage DBSCAN (§4.3.1, Song et al. 2023).
///
/// Stage 1: every lane observation is cut at the edges of a square tiling (so clusters stay
/// local and forks can be seen), each piece is buffered by ±buffer_width into a polygon
/// (boost::geometry::buffer) and pieces of one tile are clustered by DBSCAN with the overlap
/// area (intersection / smaller polygon, exact: polygon_overlap.hpp) as similarity;
/// candidates are the pieces of the same tile with touching boxes; noise pieces are dropped. Each
/// cluster (a MultiLineString) is reduced to a centreline fragment by averaging its points in
/// station bins along its principal direction.
///
/// Stage 2: fragments are clustered with a line-to-line (end-to-end) Euclidean distance and the
/// modified core-object rule MinPts <= |N_eps| <= MaxPts (MinPts = 1, MaxPts = 2): a fragment
/// end is linked to the fragment that follows it only when each of the two ends has exactly one
/// such neighbour, so a line connects to at most the line that follows it and a fork or merge
/// (an end with two followers) starts new instances. Stage-2 candidate pairs come from a
/// Boost.Geometry rtree, so the cost grows ~ n log n (lane_links.cpp).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mapfuse/aggregate/aggregator.hpp"

namespace mapfuse::aggregate {

/// One lane-line instance before vectorization.
struct LaneInstance {
  std::vector<Eigen::Vector3d> centreline;  ///< ENU, ordered along the line
  std::vector<std::size_t> observations;    ///< indices into the observation list (sorted)
  int fragments = 0;                        ///< stage-1 fragments chained into it
};

struct LaneInstantiation {
  std::vector<LaneInstance> instances;
  LaneInstantiationStats stats;
};

/// @brief Two-stage DBSCAN over the lane-line observations `indices` of `items`.
/// @param num_drives number of input drives (MinPts is capped by it).
LaneInstantiation instantiateLanes(const std::vector<Observation>& items,
                                   const std::vector<std::size_t>& indices,
                                   const LaneInstantiationParams& params, int num_drives);

}  // namespace mapfuse::aggregate
