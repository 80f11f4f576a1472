#include "mapfuse/aggregate/geometry2d.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace mapfuse::aggregate {

std::vector<Eigen::Vector3d> resamplePolyline(const std::vector<Eigen::Vector3d>& points,
                                              double step) {
  if (points.size() < 2) return points;
  std::vector<Eigen::Vector3d> out{points.front()};
  double carry = 0.0;  // arc length since the last emitted point
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Eigen::Vector3d a = points[i - 1], d = points[i] - a;
    const double len = d.norm();
    double s = step - carry;
    while (s < len) {
      out.push_back(a + d * (s / len));
      s += step;
    }
    carry = len - (s - step);
  }
  if ((out.back() - points.back()).norm() > 1e-6) out.push_back(points.back());
  return out;
}

double distanceToSegment2d(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b, Eigen::Vector3d* foot) {
  const Eigen::Vector2d ab = (b - a).head<2>(), ap = (p - a).head<2>();
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp(ap.dot(ab) / len2, 0.0, 1.0) : 0.0;
  const Eigen::Vector3d f = a + t * (b - a);
  if (foot) *foot = f;
  return (p - f).head<2>().norm();
}

double distanceToPolyline2d(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& line,
                            Eigen::Vector3d* foot) {
  if (line.empty()) return std::numeric_limits<double>::infinity();
  if (line.size() == 1) {
    if (foot) *foot = line[0];
    return (p - line[0]).head<2>().norm();
  }
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d f;
  for (std::size_t i = 1; i < line.size(); ++i) {
    const double d = distanceToSegment2d(p, line[i - 1], line[i], &f);
    if (d < best) {
      best = d;
      if (foot) *foot = f;
    }
  }
  return best;
}

Eigen::Vector2d principalAxis2d(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 2) return Eigen::Vector2d::UnitX();
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p.head<2>();
  mean /= double(points.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector2d d = p.head<2>() - mean;
    cov += d * d.transpose();
  }
  if (cov.trace() < 1e-12) return Eigen::Vector2d::UnitX();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  Eigen::Vector2d axis = es.eigenvectors().col(1).normalized();
  // canonical sign so the result does not depend on the solver
  if (axis.x() < -1e-12 || (std::abs(axis.x()) <= 1e-12 && axis.y() < 0)) axis = -axis;
  return axis;
}

std::vector<Eigen::Vector3d> binnedCentreline(const std::vector<Eigen::Vector3d>& points,
                                              double step) {
  if (points.empty()) return {};
  const Eigen::Vector2d axis = principalAxis2d(points);
  double smin = std::numeric_limits<double>::infinity(), smax = -smin;
  std::vector<double> s(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    s[i] = points[i].head<2>().dot(axis);
    smin = std::min(smin, s[i]);
    smax = std::max(smax, s[i]);
  }
  const std::size_t bins = std::size_t(std::floor((smax - smin) / step)) + 1;
  std::vector<Eigen::Vector3d> sum(bins, Eigen::Vector3d::Zero());
  std::vector<int> count(bins, 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t b = std::min(bins - 1, std::size_t((s[i] - smin) / step));
    sum[b] += points[i];
    ++count[b];
  }
  std::vector<Eigen::Vector3d> out;
  for (std::size_t b = 0; b < bins; ++b)
    if (count[b] > 0) out.push_back(sum[b] / double(count[b]));
  return out;
}

}  // namespace mapfuse::aggregate
