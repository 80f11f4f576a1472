#include "matching.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

namespace mapfuse::localize::detail {

std::vector<Match> matchPoints(const MapIndex& map, const std::vector<WorldPoint>& pts,
                               double radius, const LocalizeSettings& s, double* sum_sq) {
  std::vector<Match> out;
  *sum_sq = 0;
  for (const auto& wp : pts) {
    const TargetMatch m = map.nearest(wp.obs->key, wp.q, radius);
    if (!m.target) continue;
    Match mt;
    mt.q = wp.q;
    mt.a = m.target->a;
    mt.is_line = m.target->is_line && wp.obs->is_line;
    if (mt.is_line) {
      const Eigen::Vector2d d = m.target->b - m.target->a;
      if (d.norm() < 1e-9) continue;  // a degenerate segment: no normal
      mt.n = Eigen::Vector2d(-d.y(), d.x()).normalized();
      // eq. (L2): sigma across the line from the point's covariance and the map's
      mt.sqrt_info(0, 0) = 1.0 / std::sqrt(mt.n.dot(wp.cov * mt.n) + s.line_sigma * s.line_sigma);
    } else {
      const Eigen::Matrix2d cov =
          wp.cov + s.point_sigma * s.point_sigma * Eigen::Matrix2d::Identity();
      mt.sqrt_info = Eigen::Matrix2d(cov.inverse().llt().matrixL().transpose());
    }
    *sum_sq += m.distance * m.distance;
    out.push_back(mt);
  }
  return out;
}

}  // namespace mapfuse::localize::detail
