#pragma once
/// @file Stop lines seen whole and seen in part (private to libmapfuse/src/aggregate). A camera
/// sees only the end of a crossing road's stop line while the vehicle turns (simulate observes
/// it so, docs/simulate.md), so one stop line's observations are whole segments and pieces of
/// them. Clustering by midpoint distance split such a stop line in two (the piece's midpoint
/// lies metres from the whole line's), and averaging the ends made the map's line as short as
/// the average observation.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace mapfuse::aggregate::detail {

using Segment = std::array<Eigen::Vector3d, 2>;

/// @brief DBSCAN distance of two stop-line observations: how far the midpoint of one lies from
/// the other segment, the smaller of the two ways (0 for a piece lying on a whole line).
double stopLineDistance(const Segment& a, const Segment& b);

/// @brief One stop line from a cluster of observations with weights w (confidences): direction
/// and lateral position are weighted means; each end is the weighted mean of the member ends
/// within 0.5 m of the cluster's outer ends (the 20 % quantile of the ends along the line), so
/// pieces do not pull the ends inwards and whole observations are averaged as before.
Segment mergeStopLines(const std::vector<Segment>& members, const std::vector<double>& w,
                       std::size_t ref);

}  // namespace mapfuse::aggregate::detail
