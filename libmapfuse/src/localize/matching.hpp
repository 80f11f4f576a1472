#pragma once
/// @file Matching of observed points to the map (private; docs/localize.md step 3): each point
/// to its nearest map target of its match key within a radius, with the square-root information
/// of eq. (L2).
#include <Eigen/Core>
#include <vector>

#include "mapfuse/localize/localizer.hpp"
#include "mapfuse/localize/map_index.hpp"
#include "pose_solver.hpp"

namespace mapfuse::localize::detail {

/// An observed point in ENU at the current pose, ready to match.
struct WorldPoint {
  const ObservedPoint* obs;
  Eigen::Vector2d q;
  Eigen::Matrix2d cov;  ///< horizontal covariance in ENU, m^2
};

/// @brief Every point to its nearest target within `radius` (m); `sum_sq` receives the sum of
/// the squared distances of the matched points (m^2).
std::vector<Match> matchPoints(const MapIndex& map, const std::vector<WorldPoint>& pts,
                               double radius, const LocalizeSettings& s, double* sum_sq);

}  // namespace mapfuse::localize::detail
