#include "mapfuse/core/se3.hpp"

#include <cmath>

namespace mapfuse {

Pose3 poseFromXyzRpy(double x, double y, double z, double roll, double pitch, double yaw) {
  Pose3 T = Pose3::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& R) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  return {roll, pitch, yaw};
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

// Left Jacobian of SO(3), used to couple rotation and translation in exp/log.
static Eigen::Matrix3d leftJacobianSO3(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const Eigen::Matrix3d K = skew(phi);
  if (theta < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * K;
  const double t2 = theta * theta;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(theta)) / t2 * K +
         (theta - std::sin(theta)) / (t2 * theta) * K * K;
}

Pose3 expSE3(const Vector6d& xi) {
  const Eigen::Vector3d rho = xi.head<3>();
  const Eigen::Vector3d phi = xi.tail<3>();
  Pose3 T = Pose3::Identity();
  const double theta = phi.norm();
  T.linear() = theta < 1e-12 ? Eigen::Matrix3d(Eigen::Matrix3d::Identity() + skew(phi))
                             : Eigen::AngleAxisd(theta, phi / theta).toRotationMatrix();
  T.translation() = leftJacobianSO3(phi) * rho;
  return T;
}

Vector6d logSE3(const Pose3& T) {
  const Eigen::AngleAxisd aa(T.linear());
  const Eigen::Vector3d phi = aa.angle() * aa.axis();
  Vector6d xi;
  xi.head<3>() = leftJacobianSO3(phi).inverse() * T.translation();
  xi.tail<3>() = phi;
  return xi;
}

Pose3 interpolate(const Pose3& T0, const Pose3& T1, double alpha) {
  const Eigen::Quaterniond q0(T0.linear()), q1(T1.linear());
  Pose3 T = Pose3::Identity();
  T.linear() = q0.slerp(alpha, q1).toRotationMatrix();
  T.translation() = (1.0 - alpha) * T0.translation() + alpha * T1.translation();
  return T;
}

Matrix6d adjoint(const Pose3& T) {
  Matrix6d A = Matrix6d::Zero();
  const Eigen::Matrix3d R = T.linear();
  A.topLeftCorner<3, 3>() = R;
  A.topRightCorner<3, 3>() = skew(T.translation()) * R;
  A.bottomRightCorner<3, 3>() = R;
  return A;
}

Matrix6d composeCovariance(const Pose3& T_b_c, const Matrix6d& cov_ab, const Matrix6d& cov_bc) {
  const Matrix6d A = adjoint(T_b_c.inverse());
  return cov_bc + A * cov_ab * A.transpose();
}

Matrix6d diagonalCovariance(double sigma_translation, double sigma_rotation) {
  Vector6d d;
  d << Eigen::Vector3d::Constant(sigma_translation * sigma_translation),
      Eigen::Vector3d::Constant(sigma_rotation * sigma_rotation);
  return d.asDiagonal();
}

Eigen::Matrix3d rotateCovariance(const Eigen::Matrix3d& R, const Eigen::Matrix3d& C) {
  return R * C * R.transpose();
}

}  // namespace mapfuse
