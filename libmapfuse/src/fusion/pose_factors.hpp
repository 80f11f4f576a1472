#pragma once
/// @file Residuals of the multi-trajectory pose graph (eq. (9)-(11)) and of GBA (eq. (12)-(14)),
/// Song et al. 2023, with closed-form Jacobians in the tangent space of a pose (private to
/// libmapfuse/src/fusion). They are the residuals of the Ceres functors in factors.hpp
/// (PosePriorFactor, RelativePoseFactor) and element_factor.hpp (ElementResidual), evaluated
/// for align's own Gauss-Newton solver (pose_system.hpp): tests/fusion/test_pose_factors.cpp
/// checks them against those functors and central differences.
///
/// A pose is (t, q), T_world_body; its tangent is (dt, dphi), both in the world frame:
/// t <- t + dt, R <- Exp(dphi) R (Ceres' EigenQuaternionManifold perturbs on the left too).
/// The 4-DOF tangent (x, y, z, yaw) is columns 0, 1, 2 and 5 of the 6-DOF one.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::fusion::detail {

struct PoseVar {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  static PoseVar from(const Pose3& T) {
    return {T.translation(), Eigen::Quaterniond(T.linear()).normalized()};
  }
  Pose3 pose() const {
    Pose3 T = Pose3::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = t;
    return T;
  }
  /// Applies a tangent step (dt, dphi).
  void plus(const Vector6d& d) {
    t += d.head<3>();
    const Eigen::Vector3d phi = d.tail<3>();
    const double a = phi.norm();
    const Eigen::Quaterniond dq =
        a < 1e-12 ? Eigen::Quaterniond(1, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z())
                  : Eigen::Quaterniond(Eigen::AngleAxisd(a, phi / a));
    q = (dq * q).normalized();
  }
};

inline Eigen::Matrix3d skew3(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

/// d(2 vec(e'))/da at a = 0 for e' = [1, a] * e: w I - [v]x (Hamilton product).
inline Eigen::Matrix3d quatLeftJacobian(const Eigen::Quaterniond& e) {
  return e.w() * Eigen::Matrix3d::Identity() - skew3(e.vec());
}

/// Pose prior, eq. (9): r = L [t - t0 ; 2 vec(q0^-1 q)]; J = dr / d(tangent).
struct PriorTerm {
  Vector6d r;
  Matrix6d J;
};
inline PriorTerm priorTerm(const PoseVar& x, const PoseVar& x0, const Matrix6d& L) {
  const Eigen::Quaterniond e = x0.q.conjugate() * x.q;
  Vector6d u;
  u.head<3>() = x.t - x0.t;
  u.tail<3>() = 2.0 * e.vec();
  Matrix6d J = Matrix6d::Zero();
  J.topLeftCorner<3, 3>().setIdentity();
  J.bottomRightCorner<3, 3>() = quatLeftJacobian(e) * x0.q.toRotationMatrix().transpose();
  return {L * u, L * J};
}

/// Relative pose, eq. (10) / (11): r = L [R_a^T (t_b - t_a) - t_ab ; 2 vec(q_ab^-1 q_a^-1 q_b)].
struct RelativeTerm {
  Vector6d r;
  Matrix6d Ja, Jb;
};
inline RelativeTerm relativeTerm(const PoseVar& a, const PoseVar& b, const Eigen::Vector3d& t_ab,
                                 const Eigen::Quaterniond& q_ab, const Matrix6d& L) {
  const Eigen::Matrix3d RaT = a.q.toRotationMatrix().transpose();
  const Eigen::Vector3d d = b.t - a.t;
  const Eigen::Quaterniond e = q_ab.conjugate() * (a.q.conjugate() * b.q);
  Vector6d u;
  u.head<3>() = RaT * d - t_ab;
  u.tail<3>() = 2.0 * e.vec();
  const Eigen::Matrix3d D = quatLeftJacobian(e) * (q_ab.toRotationMatrix().transpose() * RaT);
  Matrix6d Ja = Matrix6d::Zero(), Jb = Matrix6d::Zero();
  Ja.topLeftCorner<3, 3>() = -RaT;
  Ja.topRightCorner<3, 3>() = RaT * skew3(d);
  Ja.bottomRightCorner<3, 3>() = -D;
  Jb.topLeftCorner<3, 3>() = RaT;
  Jb.bottomRightCorner<3, 3>() = D;
  return {L * u, L * Ja, L * Jb};
}

/// GBA element residual, eq. (12)-(14): d = (R_a p_a + t_a) - (R_b q_b + t_b), u = R_b dir_b;
/// a line (eq. (13)): r = s (I - u u^T) d (3 rows); a plane (eq. (14)): r = s u^T d (row 0 only,
/// rows 1-2 zero). s = 1 / sigma (times the thinning weight).
struct ElementTerm {
  Eigen::Vector3d r;
  Eigen::Matrix<double, 3, 6> Ja, Jb;
};
inline ElementTerm elementTerm(const PoseVar& a, const PoseVar& b, const Eigen::Vector3d& pa,
                               const Eigen::Vector3d& qb, const Eigen::Vector3d& dir_b, bool plane,
                               double s) {
  const Eigen::Vector3d pa_w = a.q * pa, qb_w = b.q * qb;
  const Eigen::Vector3d d = pa_w + a.t - qb_w - b.t;
  const Eigen::Vector3d u = b.q * dir_b;
  const double ud = u.dot(d);
  Eigen::Matrix3d M, N;  // dr/dd, dr/du
  ElementTerm out;
  if (plane) {
    out.r << s * ud, 0, 0;
    M.setZero();
    M.row(0) = s * u.transpose();
    N.setZero();
    N.row(0) = s * d.transpose();
  } else {
    out.r = s * (d - u * ud);
    M = s * (Eigen::Matrix3d::Identity() - u * u.transpose());
    N = -s * (ud * Eigen::Matrix3d::Identity() + u * d.transpose());
  }
  out.Ja.leftCols<3>() = M;
  out.Ja.rightCols<3>() = -M * skew3(pa_w);
  out.Jb.leftCols<3>() = -M;
  out.Jb.rightCols<3>() = M * skew3(qb_w) - N * skew3(u);
  return out;
}

/// Huber weight on a whitened squared residual s = |r|^2 (ceres::HuberLoss(delta)): rho'(s),
/// the IRLS weight of the term; its cost is rho(s) / 2.
inline double huberWeight(double s, double delta) {
  return s <= delta * delta ? 1.0 : delta / std::sqrt(s);
}
inline double huberCost(double s, double delta) {
  return 0.5 * (s <= delta * delta ? s : 2.0 * delta * std::sqrt(s) - delta * delta);
}

}  // namespace mapfuse::fusion::detail
