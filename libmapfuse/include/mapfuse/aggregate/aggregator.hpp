#pragma once
/// @file Semantic aggregation (§4.3, Song et al. 2023): ENU observations of many drives ->
/// one vector map. Lane lines: two-stage DBSCAN instantiation (lane_instantiation.hpp) then a
/// least-squares Bezier chain (bezier_fit.hpp) with dashed/solid and colour by majority vote;
/// the other classes: discrete clustering and confidence-weighted merging (discrete_merge.hpp).
#include <array>
#include <cstddef>

#include "mapfuse/aggregate/bezier_fit.hpp"
#include "mapfuse/aggregate/discrete_merge.hpp"
#include "mapfuse/aggregate/lane_instantiation.hpp"
#include "mapfuse/aggregate/observations.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::aggregate {

struct AggregatorParams {
  LaneInstantiationParams lanes;
  BezierFitParams bezier;
  DiscreteMergeParams discrete;
  double sample_step = 0.5;  ///< m, spacing of the sampled "points" of lane lines
};

struct AggregatorStats {
  LaneInstantiationStats lanes;
  std::array<std::size_t, kNumCrowdClasses> observations{};  ///< input count per class
  std::array<std::size_t, kNumCrowdClasses> instances{};     ///< output count per class
  std::array<std::size_t, kNumCrowdClasses> noise{};         ///< observations dropped as noise
  std::size_t bezier_segments = 0;
  double bezier_max_deviation = 0.0;  ///< m, largest over all lane instances
  double bezier_rms_deviation = 0.0;  ///< m, over all fitted centreline points
};

/// @brief Aggregates observations into a vector map (ENU of set.origin, ids 1..N in class
/// order, source "aggregate").
VectorMap aggregateObservations(const ObservationSet& set, const AggregatorParams& params,
                                AggregatorStats* stats = nullptr);

}  // namespace mapfuse::aggregate
