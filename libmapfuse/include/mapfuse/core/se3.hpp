#pragma once
/// @file Rigid transforms. Names carry frames: T_a_b maps points in frame b to frame a
/// (p_a = T_a_b * p_b), so T_a_c = T_a_b * T_b_c.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mapfuse {

using Pose3 = Eigen::Isometry3d;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// @brief Pose from translation and roll/pitch/yaw (rad), R = Rz(yaw) * Ry(pitch) * Rx(roll).
Pose3 poseFromXyzRpy(double x, double y, double z, double roll, double pitch, double yaw);

/// @brief Roll, pitch, yaw (rad) of a rotation, inverse of the convention above.
Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& R);

/// @brief Exponential map of se(3); tangent ordered (rho_x, rho_y, rho_z, phi_x, phi_y, phi_z).
Pose3 expSE3(const Vector6d& xi);

/// @brief Logarithm of SE(3), inverse of expSE3.
Vector6d logSE3(const Pose3& T);

/// @brief Skew-symmetric matrix of v, so that skew(v) * w = v x w.
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

/// @brief Geodesic interpolation between two poses, alpha in [0, 1]
/// (slerp on rotation, linear on translation).
Pose3 interpolate(const Pose3& T0, const Pose3& T1, double alpha);

/// @brief Adjoint of T, mapping tangent vectors (rho, phi) at identity through T: Ad(T) xi.
Matrix6d adjoint(const Pose3& T);

/// @brief Covariance (rho, phi order) of T_a_c = T_a_b * T_b_c from independent covariances,
/// first-order: Sigma_ac = Sigma_bc + Ad(T_b_c^-1) Sigma_ab Ad(T_b_c^-1)^T, right perturbation.
Matrix6d composeCovariance(const Pose3& T_b_c, const Matrix6d& cov_ab, const Matrix6d& cov_bc);

/// @brief Diagonal covariance from translation sigma (m) and rotation sigma (rad).
Matrix6d diagonalCovariance(double sigma_translation, double sigma_rotation);

/// @brief Rotates a 3x3 covariance: R * C * R^T.
Eigen::Matrix3d rotateCovariance(const Eigen::Matrix3d& R, const Eigen::Matrix3d& C);

}  // namespace mapfuse
