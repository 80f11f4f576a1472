#pragma once
/// @file Ceres cost functors shared by georef, the multi-trajectory pose graph and GBA (private to
/// libmapfuse/src/fusion; Ceres stays out of public headers). A pose is two parameter blocks:
/// translation t[3] (Euclidean) and unit quaternion q[4] (Eigen order x, y, z, w, with
/// ceres::EigenQuaternionManifold), meaning T_world_body.
#include <ceres/autodiff_manifold.h>
#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::fusion::detail {

/// Parameter storage for one pose.
struct PoseParams {
  double t[3];
  double q[4];  ///< x, y, z, w
  void set(const Pose3& T) {
    Eigen::Map<Eigen::Vector3d> tm(t);
    tm = T.translation();
    Eigen::Map<Eigen::Quaterniond> qm(q);
    qm = Eigen::Quaterniond(T.linear()).normalized();
  }
  Pose3 get() const {
    Pose3 T = Pose3::Identity();
    T.linear() = Eigen::Map<const Eigen::Quaterniond>(q).normalized().toRotationMatrix();
    T.translation() = Eigen::Map<const Eigen::Vector3d>(t);
    return T;
  }
};

/// @brief Square-root information (upper-triangular L^T with L L^T = info) of a covariance.
template <int N>
Eigen::Matrix<double, N, N> sqrtInformation(const Eigen::Matrix<double, N, N>& cov) {
  const Eigen::Matrix<double, N, N> info = cov.inverse();
  return info.llt().matrixL().transpose();
}

/// Relative pose factor, eq. (5) / (10): r = sqrt_info * [R_a^T (t_b - t_a) - t_ab ; 2 vec(q_ab^-1
/// q_a^-1 q_b)] (translation error in frame a, rotation error as a small right perturbation).
struct RelativePoseFactor {
  RelativePoseFactor(const Pose3& T_a_b, const Matrix6d& sqrt_info)
      : t_ab(T_a_b.translation()), q_ab(Eigen::Quaterniond(T_a_b.linear())), L(sqrt_info) {}
  template <class T>
  bool operator()(const T* ta, const T* qa, const T* tb, const T* qb, T* res) const {
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> pa(ta), pb(tb);
    Eigen::Map<const Eigen::Quaternion<T>> Qa(qa), Qb(qb);
    const Eigen::Quaternion<T> Qa_inv = Qa.conjugate();
    const Eigen::Matrix<T, 3, 1> t_est = Qa_inv * (pb - pa);
    const Eigen::Quaternion<T> dq = q_ab.template cast<T>().conjugate() * (Qa_inv * Qb);
    Eigen::Matrix<T, 6, 1> r;
    r.template head<3>() = t_est - t_ab.template cast<T>();
    r.template tail<3>() = T(2.0) * dq.vec();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> out(res);
    out = L.template cast<T>() * r;
    return true;
  }
  static ceres::CostFunction* create(const Pose3& T_a_b, const Matrix6d& sqrt_info) {
    return new ceres::AutoDiffCostFunction<RelativePoseFactor, 6, 3, 4, 3, 4>(
        new RelativePoseFactor(T_a_b, sqrt_info));
  }
  Eigen::Vector3d t_ab;
  Eigen::Quaterniond q_ab;
  Matrix6d L;
};

/// Position factor between two keyframes, eq. (6): the body origin interpolated at alpha,
/// (1 - alpha) t_a + alpha t_b, equals a measured world position (GPS, in ENU).
struct InterpolatedPositionFactor {
  InterpolatedPositionFactor(const Eigen::Vector3d& p, double alpha,
                             const Eigen::Matrix3d& sqrt_info)
      : p(p), alpha(alpha), L(sqrt_info) {}
  template <class T>
  bool operator()(const T* ta, const T* tb, T* res) const {
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> pa(ta), pb(tb);
    const Eigen::Matrix<T, 3, 1> e = T(1.0 - alpha) * pa + T(alpha) * pb - p.template cast<T>();
    Eigen::Map<Eigen::Matrix<T, 3, 1>> out(res);
    out = L.template cast<T>() * e;
    return true;
  }
  static ceres::CostFunction* create(const Eigen::Vector3d& p, double alpha,
                                     const Eigen::Matrix3d& sqrt_info) {
    return new ceres::AutoDiffCostFunction<InterpolatedPositionFactor, 3, 3, 3>(
        new InterpolatedPositionFactor(p, alpha, sqrt_info));
  }
  Eigen::Vector3d p;
  double alpha;
  Eigen::Matrix3d L;
};

/// Full pose prior (eq. (9)): r = sqrt_info * [t - t0 ; 2 vec(q0^-1 q)].
struct PosePriorFactor {
  PosePriorFactor(const Pose3& T0, const Matrix6d& sqrt_info)
      : t0(T0.translation()), q0(Eigen::Quaterniond(T0.linear())), L(sqrt_info) {}
  template <class T>
  bool operator()(const T* t, const T* q, T* res) const {
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> p(t);
    Eigen::Map<const Eigen::Quaternion<T>> Q(q);
    Eigen::Matrix<T, 6, 1> r;
    r.template head<3>() = p - t0.template cast<T>();
    r.template tail<3>() = T(2.0) * (q0.template cast<T>().conjugate() * Q).vec();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> out(res);
    out = L.template cast<T>() * r;
    return true;
  }
  static ceres::CostFunction* create(const Pose3& T0, const Matrix6d& sqrt_info) {
    return new ceres::AutoDiffCostFunction<PosePriorFactor, 6, 3, 4>(
        new PosePriorFactor(T0, sqrt_info));
  }
  Eigen::Vector3d t0;
  Eigen::Quaterniond q0;
  Matrix6d L;
};

/// Gravity (tilt) prior on one pose: the world's up axis seen in the body frame, R^T e_z, equals
/// the one the odometry measured (its frame has z up: IMU-aided odometry observes gravity, so
/// roll and pitch do not drift). Without it a straight drive's roll about its direction of travel
/// is free in the GPS pose graph (positions on a line fix no rotation about that line).
/// r = (R^T e_z - up_body) / sigma; 3 residuals of rank 2, yaw is left free.
struct GravityFactor {
  GravityFactor(const Eigen::Vector3d& up_body, double sigma) : up(up_body), inv_sigma(1 / sigma) {}
  template <class T>
  bool operator()(const T* q, T* res) const {
    Eigen::Map<const Eigen::Quaternion<T>> Q(q);
    const Eigen::Matrix<T, 3, 1> e = Q.conjugate() * Eigen::Matrix<T, 3, 1>(T(0), T(0), T(1));
    for (int i = 0; i < 3; ++i) res[i] = T(inv_sigma) * (e[i] - T(up[i]));
    return true;
  }
  static ceres::CostFunction* create(const Eigen::Vector3d& up_body, double sigma) {
    return new ceres::AutoDiffCostFunction<GravityFactor, 3, 4>(new GravityFactor(up_body, sigma));
  }
  Eigen::Vector3d up;
  double inv_sigma;
};

/// Heading-only update of a unit quaternion (Eigen order x, y, z, w): q <- Rz(delta) q, a
/// rotation about the world's up axis. Roll and pitch stay as they are (observed by gravity: the
/// 4-DOF pose graph of VINS-Mono, Qin et al. 2018); tangent size 1.
struct YawPlus {
  template <class T>
  bool Plus(const T* x, const T* delta, T* x_plus) const {
    const Eigen::Quaternion<T> dq(ceres::cos(delta[0] / T(2)), T(0), T(0),
                                  ceres::sin(delta[0] / T(2)));
    Eigen::Map<Eigen::Quaternion<T>> out(x_plus);
    out = dq * Eigen::Map<const Eigen::Quaternion<T>>(x);
    return true;
  }
  template <class T>
  bool Minus(const T* y, const T* x, T* delta) const {
    const Eigen::Quaternion<T> dq = Eigen::Map<const Eigen::Quaternion<T>>(y) *
                                    Eigen::Map<const Eigen::Quaternion<T>>(x).conjugate();
    delta[0] = T(2) * ceres::atan2(dq.z(), dq.w());
    return true;
  }
};

/// @brief Adds a pose's two parameter blocks: the full quaternion manifold (6 DOF) or, with
/// `yaw_only`, heading only (4 DOF: x, y, z, yaw).
inline void addPose(ceres::Problem& problem, PoseParams& p, bool yaw_only = false) {
  problem.AddParameterBlock(p.t, 3);
  if (yaw_only)
    problem.AddParameterBlock(p.q, 4, new ceres::AutoDiffManifold<YawPlus, 4, 1>);
  else
    problem.AddParameterBlock(p.q, 4, new ceres::EigenQuaternionManifold);
}

}  // namespace mapfuse::fusion::detail
