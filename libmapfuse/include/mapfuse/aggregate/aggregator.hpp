#pragma once
/// @file Semantic aggregation (§4.3, Song et al. 2023): ENU observations of many drives ->
/// one vector map. Lane lines: two-stage DBSCAN instantiation (lane_instantiation.cpp) then a
/// least-squares Bezier chain (bezier_fit.cpp) with dashed/solid and colour by majority vote;
/// the other classes: discrete clustering and confidence-weighted merging (discrete_merge.cpp).
/// Parameters: settings.hpp.
#include <array>
#include <cstddef>

#include "mapfuse/aggregate/observations.hpp"
#include "mapfuse/aggregate/settings.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::aggregate {

/// What lane instantiation did (stage 1 and stage 2).
struct LaneInstantiationStats {
  std::size_t pieces = 0;         ///< observation pieces after tiling
  std::size_t comparisons = 0;    ///< stage-1 overlap tests (pairs of pieces with touching boxes)
  std::size_t noise_pieces = 0;   ///< dropped by stage 1
  std::size_t fragments = 0;      ///< stage-1 clusters (after merging split ones)
  std::size_t links = 0;          ///< stage-2 links
  std::size_t branch_ends = 0;    ///< fragment ends with more than one follower (forks/merges)
  std::size_t dropped_short = 0;  ///< instances below min_instance_length
};

/// What the grid-vote baseline did (method grid_vote, grid_vote.hpp).
struct GridVoteStats {
  std::size_t cells = 0;           ///< cells holding at least one vote
  std::size_t painted = 0;         ///< votes cast (one per observation and cell)
  std::size_t voted_cells = 0;     ///< cells that took a class (>= min_votes)
  std::size_t conflict_cells = 0;  ///< cells with votes of more than one class
  std::size_t min_votes_used = 0;  ///< min_votes after capping by the number of drives
  std::array<std::size_t, kNumCrowdClasses> class_cells{};  ///< cells each class won
};

/// What aggregation did, per class and per step.
struct AggregatorStats {
  LaneInstantiationStats lanes;
  GridVoteStats grid;                                        ///< method grid_vote only
  std::array<std::size_t, kNumCrowdClasses> observations{};  ///< input count per class
  std::array<std::size_t, kNumCrowdClasses> instances{};     ///< output count per class
  std::array<std::size_t, kNumCrowdClasses> noise{};         ///< observations dropped as noise
  std::size_t bezier_segments = 0;
  double bezier_max_deviation = 0.0;  ///< m, largest over all lane instances
  double bezier_rms_deviation = 0.0;  ///< m, over all fitted centreline points
};

/// @brief Aggregates observations into a vector map with params.method: "dbscan_bezier" (the
/// above) or "grid_vote" (Qin et al. 2021: the ground classes by grid voting, grid_vote.hpp; the
/// elevated ones, which that system does not map, by the same discrete merging). The map is in
/// the ENU of set.origin, ids 1..N in class order, source "aggregate".
VectorMap aggregateObservations(const ObservationSet& set, const AggregatorParams& params,
                                AggregatorStats* stats = nullptr);

}  // namespace mapfuse::aggregate
