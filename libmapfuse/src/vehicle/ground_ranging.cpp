#include "mapfuse/vehicle/ground_ranging.hpp"

#include <Eigen/LU>

namespace mapfuse::vehicle {

std::optional<Eigen::Vector3d> backProjectToGround(const Eigen::Vector2d& pixel,
                                                   const Eigen::Matrix3d& K_inv,
                                                   const GroundPlane& plane) {
  const Eigen::Vector3d ray = K_inv * Eigen::Vector3d(pixel.x(), pixel.y(), 1.0);
  const double denom = plane.normal_cam.dot(ray);
  // The plane lies below the camera (n points up): only rays going down (n^T r < 0) hit it.
  if (!(denom < -1e-9)) return std::nullopt;
  const Eigen::Vector3d X = -plane.height * ray / denom;  // eq. (1), Song et al. 2023
  if (!(X.z() > 0.0)) return std::nullopt;
  return X;
}

std::optional<GroundPoint> rangeGroundPixel(const Eigen::Vector2d& pixel, const Eigen::Matrix3d& K,
                                            const GroundPlane& plane, const RangingSettings& s) {
  const Eigen::Matrix3d K_inv = K.inverse();
  const auto X = backProjectToGround(pixel, K_inv, plane);
  if (!X) return std::nullopt;
  const double range = X->norm();
  if (range < s.min_range || range > s.max_range) return std::nullopt;

  // First-order propagation: columns = dX/d(u, v, h, pitch, roll), central differences.
  auto eval = [&](int k, double step) -> Eigen::Vector3d {
    Eigen::Vector2d px = pixel;
    GroundPlane pl = plane;
    if (k == 0) px.x() += step;
    if (k == 1) px.y() += step;
    if (k == 2) pl.height += step;
    if (k == 3) pl.normal_cam = tiltNormal(plane.normal_cam, step, 0.0);
    if (k == 4) pl.normal_cam = tiltNormal(plane.normal_cam, 0.0, step);
    const auto Y = backProjectToGround(px, K_inv, pl);
    return Y ? *Y : *X;
  };
  const double steps[5] = {0.5, 0.5, 0.01, 1e-4, 1e-4};
  const double sigmas[5] = {s.sigma_pixel, s.sigma_pixel, s.sigma_height, s.sigma_attitude,
                            s.sigma_attitude};
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector3d d = (eval(k, steps[k]) - eval(k, -steps[k])) / (2.0 * steps[k]);
    cov += sigmas[k] * sigmas[k] * d * d.transpose();
  }
  cov += Eigen::Matrix3d::Identity() * 1e-6;  // keep it positive definite
  return GroundPoint{*X, cov};
}

std::vector<GroundPoint> rangeGroundPolyline(const std::vector<Eigen::Vector2d>& pixels,
                                             const Eigen::Matrix3d& K, const GroundPlane& plane,
                                             const RangingSettings& settings) {
  std::vector<GroundPoint> out;
  out.reserve(pixels.size());
  for (const auto& px : pixels)
    if (auto g = rangeGroundPixel(px, K, plane, settings)) out.push_back(*g);
  return out;
}

}  // namespace mapfuse::vehicle
