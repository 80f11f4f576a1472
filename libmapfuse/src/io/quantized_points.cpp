#include "quantized_points.hpp"

#include <cmath>
#include <string>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {
namespace {
Eigen::Matrix<int64_t, 3, 1> toUnits(const Eigen::Vector3d& p, double q) {
  const Eigen::Vector3d units = (p / q).array().round().matrix();
  // 2^62 units: a cast beyond int64 would be undefined, and deltas of two such values still fit.
  if (!(units.cwiseAbs().maxCoeff() < 4.6e18))
    throw InputError("coordinate " + bounds::numberText(p.cwiseAbs().maxCoeff()) +
                     " m has no integer in units of the quantum " + bounds::numberText(q) + " m");
  return units.cast<int64_t>();
}
}  // namespace

Json quantizedPointsToJson(const std::vector<Eigen::Vector3d>& points, double q) {
  Json out = Json::array();
  Eigen::Matrix<int64_t, 3, 1> prev = Eigen::Matrix<int64_t, 3, 1>::Zero();
  for (const auto& p : points) {
    const Eigen::Matrix<int64_t, 3, 1> u = toUnits(p, q);
    for (int k = 0; k < 3; ++k) out.push_back(u[k] - prev[k]);
    prev = u;
  }
  return out;
}

std::vector<Eigen::Vector3d> quantizedPointsFromJson(const JsonView& v, double q) {
  if (v.size() == 0 || v.size() % 3 != 0)
    v.fail("needs whole 3D points (a non-empty multiple of 3 integers), got " +
           std::to_string(v.size()) + " numbers");
  // Every running sum stays within the coordinate bound, so no sum can overflow: each delta
  // is checked against the room left before it is added.
  const auto limit = int64_t(std::floor(bounds::kMaxCoordinate / q));
  std::vector<Eigen::Vector3d> points;
  Eigen::Matrix<int64_t, 3, 1> u = Eigen::Matrix<int64_t, 3, 1>::Zero();
  for (std::size_t i = 0; i < v.size(); i += 3) {
    for (int k = 0; k < 3; ++k) {
      const JsonView d = v.at(i + std::size_t(k));
      const int64_t delta = d.integer();
      if (delta < -limit - u[k] || delta > limit - u[k])
        d.fail("delta-coded coordinate leaves " +
               bounds::rangeText(-bounds::kMaxCoordinate, bounds::kMaxCoordinate) + " m");
      u[k] += delta;
    }
    points.push_back(u.cast<double>() * q);
  }
  return points;
}

std::optional<std::vector<Eigen::Vector3d>> chainControlPoints(
    const std::vector<BezierSegment>& chain, double q) {
  std::vector<Eigen::Vector3d> points;
  for (std::size_t s = 0; s < chain.size(); ++s) {
    if (s > 0 && toUnits(chain[s][0], q) != toUnits(chain[s - 1][3], q)) return std::nullopt;
    for (int k = s == 0 ? 0 : 1; k < 4; ++k) points.push_back(chain[s][k]);
  }
  return points;
}

std::vector<BezierSegment> chainFromControlPoints(const std::vector<Eigen::Vector3d>& points,
                                                  const JsonView& v) {
  if (points.size() < 4 || (points.size() - 1) % 3 != 0)
    v.fail("a Bezier chain needs 3n+1 control points (n >= 1), got " +
           std::to_string(points.size()));
  std::vector<BezierSegment> chain;
  for (std::size_t i = 0; i + 3 < points.size(); i += 3)
    chain.push_back({points[i], points[i + 1], points[i + 2], points[i + 3]});
  return chain;
}

}  // namespace mapfuse::io
