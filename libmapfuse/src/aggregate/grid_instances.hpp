#pragma once
/// @file Vectorisation of the voted grid (grid_vote.hpp) with this project's own steps, so that
/// evaluate scores both aggregation methods on equal terms: the cells each class won are grouped
/// into 8-connected components; lane-line components, cut at the lane tiling (tile_size) like
/// the observation pieces of §4.3.1, become stage-1 fragments (centreline binned along the
/// principal axis) that the stage-2 linking and the Bezier fit of eq. (15), Song et al. 2023,
/// turn into instances; a stop-line component becomes the segment between its extreme cells
/// along its principal axis, a crosswalk component the convex hull of its cells simplified to a
/// quadrilateral (core/area_outline.hpp), an arrow component its oriented bounding rectangle.
#include <vector>

#include "grid_vote.hpp"
#include "mapfuse/aggregate/aggregator.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::aggregate {

/// @brief The instances of the ground classes by grid voting (lane lines first, then the other
/// ground classes in class order; ids left 0). Fills stats.grid and stats.lanes (stage 2).
/// @param num_drives number of input drives (min_votes is capped by it).
std::vector<MapInstance> gridVoteInstances(const std::vector<Observation>& items,
                                           const AggregatorParams& params, int num_drives,
                                           AggregatorStats& stats);

}  // namespace mapfuse::aggregate
