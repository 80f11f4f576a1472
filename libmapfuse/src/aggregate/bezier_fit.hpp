#pragma once
/// @file Vectorization of a lane instance (§4.3.2, eq. (15), Song et al. 2023): a chain of cubic
/// Bezier curves fitted by least squares to the instance's centreline, split until every point
/// lies within a stated maximum deviation (Schneider's algorithm: chord-length parameters,
/// Newton re-parametrisation, G1 tangents at the joints).
#include <Eigen/Core>
#include <vector>

#include "mapfuse/aggregate/aggregator.hpp"
#include "mapfuse/aggregate/settings.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::aggregate {

struct BezierFitResult {
  std::vector<BezierSegment> chain;
  double max_deviation = 0.0;  ///< m, achieved (point-to-curve at the fitted parameters)
  double rms_deviation = 0.0;  ///< m
};

/// @brief Least-squares cubic Bezier through fixed end points p.front(), p.back() with fixed
/// unit end tangents t0 (leaving P0) and t1 (entering P3, pointing backwards from P3):
/// P1 = P0 + a t0, P2 = P3 + b t1, (a, b) minimising sum ||B(u_i) - p_i||^2 (eq. (15)).
/// @param u parameters in [0, 1], one per point (updated by Newton steps when iterations > 0).
BezierSegment fitCubicBezier(const std::vector<Eigen::Vector3d>& p, std::vector<double>& u,
                             const Eigen::Vector3d& t0, const Eigen::Vector3d& t1, int iterations);

/// @brief Fits a G1 Bezier chain to an ordered polyline (at least 2 points).
BezierFitResult fitBezierChain(const std::vector<Eigen::Vector3d>& points,
                               const BezierFitParams& params);

/// @brief A lane-line instance (class and geometry only) from a lane's centreline: the fitted
/// chain (eq. (15)) and its points every `params.sample_step`. The fit's segments and largest
/// deviation go into `stats`; its squared deviation times the centreline's points into
/// `sum_sq`, the points into `count` (for the RMS over all lanes).
MapInstance fittedLaneLine(const std::vector<Eigen::Vector3d>& centreline,
                           const AggregatorParams& params, AggregatorStats& stats, double& sum_sq,
                           std::size_t& count);

}  // namespace mapfuse::aggregate
