#include "path_surface.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace mapfuse::vehicle {
namespace {
/// Path searched ahead for the frame abreast, beyond the farthest ranged point: the path bends,
/// and a point at max_range is passed after more than max_range of path.
constexpr double kReachMargin = 1.5;
/// Share of the reach the parabola also spans behind the frame (its d ∈ [-share reach, reach]):
/// measured on the 8 % and the flat world (tests/vehicle/test_path_surface.cpp), 0.5 left the
/// flat world's far lane points 16 % worse than the plane under the camera, 1.0 8 %, 2.0 smooths
/// the hills' bends away (0.18 m against 0.13 m on the 8 % world).
constexpr double kFitBehindShare = 1.0;
/// Frames the parabola needs (fewer, e.g. at a standstill or the drive's ends: no bend).
constexpr int kFitMinFrames = 10;

/// Least-squares c of z ≈ a + b d + c d² over frames [lo, hi) (d relative to frame i); 0 when
/// the frames do not span enough path for a parabola.
double fitBend(const std::vector<double>& d, const std::vector<double>& z, std::size_t i,
               std::size_t lo, std::size_t hi, double span_min) {
  if (int(hi - lo) < kFitMinFrames || d[hi - 1] - d[lo] < span_min) return 0.0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t k = lo; k < hi; ++k) {
    const double x = d[k] - d[i];
    const Eigen::Vector3d row(1.0, x, x * x);
    A += row * row.transpose();
    b += row * (z[k] - z[i]);
  }
  const Eigen::Vector3d coef = A.ldlt().solve(b);
  return std::isfinite(coef.z()) ? coef.z() : 0.0;
}
}  // namespace

PathSurface::PathSurface(const std::vector<Pose3>& T_odom_body, const Pose3& T_body_cam,
                         const std::vector<GroundPlane>& planes, const RangingSettings& settings)
    : T_odom_body_(T_odom_body),
      T_body_cam_(T_body_cam),
      planes_(planes),
      max_offset_(settings.path_max_offset),
      reach_(kReachMargin * settings.max_range) {
  const std::size_t n = T_odom_body.size();
  distance_.assign(n, 0.0);
  bend_.assign(n, 0.0);
  Eigen::Vector3d up = Eigen::Vector3d::Zero();  // the drive's mean up axis (any odom frame)
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0)
      distance_[k] = distance_[k - 1] +
                     (T_odom_body[k].translation() - T_odom_body[k - 1].translation()).norm();
    up += T_odom_body[k].linear().col(2);
  }
  if (n == 0 || !(up.norm() > 0)) return;
  up.normalize();
  std::vector<double> z(n);
  for (std::size_t k = 0; k < n; ++k) z[k] = up.dot(T_odom_body[k].translation());
  std::size_t lo = 0, hi = 0;  // frames [lo, hi) with d in [-share reach, reach] around frame i
  for (std::size_t i = 0; i < n; ++i) {
    while (distance_[lo] < distance_[i] - kFitBehindShare * reach_) ++lo;
    while (hi < n && distance_[hi] <= distance_[i] + reach_) ++hi;
    bend_[i] = fitBend(distance_, z, i, lo, hi, 0.5 * reach_);
  }
}

std::optional<std::size_t> PathSurface::frameAbreast(std::size_t i,
                                                     const Eigen::Vector3d& p_odom) const {
  for (std::size_t j = i + 1; j < T_odom_body_.size(); ++j) {
    if (distance_[j] - distance_[i] > reach_) return std::nullopt;
    const Eigen::Vector3d q = T_odom_body_[j].inverse() * p_odom;  // body j: x ahead
    if (q.x() > 0.0) continue;
    // Passed between j - 1 and j: the nearer of the two along x.
    std::size_t k = j;
    if (j - 1 > i) {
      const double x_prev = (T_odom_body_[j - 1].inverse() * p_odom).x();
      if (std::abs(x_prev) < std::abs(q.x())) k = j - 1;
    }
    const Eigen::Vector3d qk = T_odom_body_[k].inverse() * p_odom;
    if (std::abs(qk.y()) > max_offset_) return std::nullopt;
    return k;
  }
  return std::nullopt;
}

double PathSurface::riseAhead(std::size_t i, std::size_t j) const {
  const double d = distance_[j] - distance_[i];
  return bend_[i] * d * d;
}

std::optional<GroundPoint> PathSurface::range(std::size_t i, const Eigen::Vector2d& pixel,
                                              const Eigen::Matrix3d& K,
                                              const RangingSettings& ranging, bool* on_path) const {
  if (on_path) *on_path = false;
  const Eigen::Matrix3d K_inv = K.inverse();
  GroundPlane plane = planes_[i];
  auto X = backProjectToGround(pixel, K_inv, plane);  // eq. (1) under the camera
  if (!X) return std::nullopt;
  const Pose3 T_odom_cam_i = T_odom_body_[i] * T_body_cam_;
  std::optional<std::size_t> used;
  for (int it = 0; it < kMaxIterations; ++it) {
    const auto j = frameAbreast(i, T_odom_cam_i * *X);
    if (!j || j == used) break;
    GroundPlane ahead = planes_[i];  // the tangent plane raised to the road abreast
    ahead.height -= riseAhead(i, *j);
    if (!(ahead.height > 0.0)) break;
    const auto again = backProjectToGround(pixel, K_inv, ahead);  // eq. (1) on the road ahead
    if (!again) break;
    X = again;
    plane = ahead;
    used = j;
  }
  // The band and the covariance on the plane finally used.
  auto g = rangeGroundPixel(pixel, K, plane, ranging);
  if (g && on_path) *on_path = used.has_value();
  return g;
}

}  // namespace mapfuse::vehicle
