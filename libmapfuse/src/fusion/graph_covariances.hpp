#pragma once
/// @file The covariances of align's pose graph terms built from the georeferenced keyframes:
/// the pose prior of eq. (9) and the odometry between consecutive keyframes of eq. (10), Song et
/// al. 2023 (private to libmapfuse/src/fusion; the Ceres reference of tests/fusion uses them).
#include <Eigen/Cholesky>
#include <algorithm>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/fusion/align.hpp"

namespace mapfuse::fusion::detail {

/// @brief Square-root information (upper-triangular L^T with L L^T = info) of a covariance.
inline Matrix6d sqrtInformation(const Matrix6d& cov) {
  const Matrix6d info = cov.inverse();
  return info.llt().matrixL().transpose();
}

/// @brief Eq. (9): georef's position covariance of the keyframe (plus 1e-6 m^2 so that it
/// stays invertible) and `prior_rotation_sigma` on the attitude.
inline Matrix6d priorCovariance(const Keyframe& kf, const AlignSettings& s) {
  Matrix6d cov = Matrix6d::Zero();
  cov.topLeftCorner<3, 3>() = kf.covariance.topLeftCorner<3, 3>();
  cov.diagonal().tail<3>().setConstant(s.prior_rotation_sigma * s.prior_rotation_sigma);
  cov.topLeftCorner<3, 3>().diagonal().array() += 1e-6;
  return cov;
}

/// @brief Eq. (10): odometry sigma growing with the distance `rel` moves (m; a tenth of it, rad),
/// floored at `odom_min_sigma`.
inline Matrix6d odometryCovariance(const Pose3& rel, const AlignSettings& s) {
  const double d = rel.translation().norm();
  return diagonalCovariance(std::max(s.odom_min_sigma, s.odom_sigma_per_m * d),
                            std::max(0.1 * s.odom_min_sigma, 0.1 * s.odom_sigma_per_m * d));
}

}  // namespace mapfuse::fusion::detail
