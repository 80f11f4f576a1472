#pragma once
/// @file Joins lane lines that a map file splits into pieces (docs/simulate.md "Lanelet2 maps"):
/// Lanelet2 maps end a line string where a lanelet ends, OpenDRIVE where a lane section or a
/// road mark record ends, but the painted marking runs on (a dashed line keeps its phase).
#include <functional>
#include <vector>

#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::sim {

/// @brief Joins lane-line instances end to end where exactly two line ends meet within
/// `tolerance` (m), both lines have the same attributes and run on in the same direction
/// (within 45 degrees). A chain takes the place and id of the lowest-index piece at one of its
/// free ends, collects its pieces' `source_ids` (or ids) and notes; a closed loop ends on its
/// first point. Other classes, and lines meeting at forks, are left as they are.
/// @param may_join optional extra condition on a join of instance a's end `side_a` (0 front,
/// 1 back) to instance b's end `side_b` (e.g. the ends are the same map node).
/// @return how many joins were made.
int joinLineChains(std::vector<MapInstance>& instances, double tolerance,
                   const std::function<bool(const MapInstance& a, int side_a, const MapInstance& b,
                                            int side_b)>& may_join = {});

}  // namespace mapfuse::sim
