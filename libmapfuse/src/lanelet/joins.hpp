#pragma once
/// @file Lane lines that continue each other (docs/formats.md "Lanelet2 export"): aggregation can
/// break one painted line into instances whose facing ends leave a gap (0.1-0.9 m on the
/// procedural worlds, 2.4 m once) or overlap (1-2.5 m), typically a chain of 5-6 m fragments
/// between two long pieces. Two lanelets along such a line then end and begin at different nodes
/// of that bound, so Lanelet2's routing graph has no edge from one to the next although the lane
/// runs on (issue 35: 12 of 220 drive pairs on seed 13 without a route). Joining the facing ends
/// at one point gives both lines one end node, and the cuts that pair them with the line across
/// then fall together.
#include <Eigen/Core>
#include <vector>

namespace mapfuse::lanelet::detail {

/// What joinLineEnds did.
struct LineJoins {
  int joined = 0;            ///< pairs of ends joined
  double max_gap = 0.0;      ///< m, widest gap closed
  double max_overlap = 0.0;  ///< m, longest overlap trimmed
};

/// @brief Joins the facing ends of lines that continue each other: the ends face each other
/// (directions over their last 2 m within 25 degrees of opposite), lie within `max_join` (m)
/// along that direction, as a gap or an overlap, and within 0.5 m across it (lane lines are
/// a lane width, at least 2 m, apart), and each is the other's nearest such end. Both lines then
/// end at the midpoint of the two ends: a gap is bridged by one segment on each side, an overlap
/// is trimmed from both lines (vertices beyond the midpoint dropped). An end whose line would
/// keep fewer than two points stays as it is. `max_join` 0 joins nothing.
LineJoins joinLineEnds(std::vector<std::vector<Eigen::Vector3d>>& lines, double max_join);

}  // namespace mapfuse::lanelet::detail
