#pragma once
/// @file The per-keyframe least-squares problem of the localiser (private; Ceres stays out of the
/// public headers). Unknown: a planar correction x = (dx, dy, dtheta) of the current pose, a
/// rotation by dtheta about the pose's position c followed by the shift d (docs/localize.md):
///   eq. (L1)  q' = c + d + R(dtheta) (q - c)
///   eq. (L2)  r_line = n^T (q' - a) / sigma_line,   r_point = (q' - m) / sigma_point
///   eq. (L3)  r_gps = (c + d - t_gps) / sigma_gps, (psi + dtheta - psi_gps) / sigma_psi;
///             r_odo = (c + d - t_pred) / sigma_m(s),  (psi + dtheta - psi_pred) / sigma_mpsi(s)
///   eq. (L4)  min_x  sum rho_Cauchy(|r_match|^2) + |r_gps|^2 + |r_odo|^2
#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <vector>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::localize::detail {

/// Heading of a pose (rad, from east, counter-clockwise).
inline double yawOf(const Pose3& T) {
  return std::atan2(T.linear()(1, 0), T.linear()(0, 0));
}

/// The pose after a planar correction x = (dx, dy, dtheta) about its own position (eq. L1 applied
/// to the whole pose).
inline Pose3 corrected(const Pose3& T, const Eigen::Vector3d& x) {
  Pose3 out = T;
  out.linear() = Eigen::AngleAxisd(x.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix() * T.linear();
  out.translation().head<2>() += x.head<2>();
  return out;
}

/// One observed point matched to a map target, in ENU (2D, m).
struct Match {
  Eigen::Vector2d q;  ///< observed point at the current pose
  Eigen::Vector2d a;  ///< target point, or a point of the target line
  Eigen::Vector2d n;  ///< unit normal of the target line (lines only)
  bool is_line = false;
  /// square-root information: lines, 1 / sigma across the line in (0, 0); points, the 2x2
  Eigen::Matrix2d sqrt_info = Eigen::Matrix2d::Identity();
};

/// A planar pose prior: position (m) and heading (rad) with the square-root information of
/// (x, y, yaw).
struct PlanarPrior {
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  double yaw = 0.0;
  Eigen::Matrix3d sqrt_info = Eigen::Matrix3d::Identity();
};

struct SolveInput {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();  ///< current position (rotation centre), m
  double yaw = 0.0;                             ///< current heading, rad
  std::vector<Match> matches;
  double robust_scale = 2.0;  ///< Cauchy scale in sigmas
  PlanarPrior gps;
  std::optional<PlanarPrior> motion;  ///< absent when there is no prediction
  int max_iterations = 20;
};

struct SolveOutput {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  ///< (dx m, dy m, dtheta rad)
  int iterations = 0;
  bool converged = false;
  /// information of x at the solution (matches with their Cauchy weights, and the priors)
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
};

/// @brief Solves eq. (L4) for the correction.
SolveOutput solvePlanarCorrection(const SolveInput& in);

/// @brief eq. (L1) applied to a point.
Eigen::Vector2d applyCorrection(const Eigen::Vector3d& x, const Eigen::Vector2d& c,
                                const Eigen::Vector2d& q);

}  // namespace mapfuse::localize::detail
