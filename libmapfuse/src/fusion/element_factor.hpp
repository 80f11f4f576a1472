#pragma once
/// @file GBA element residual (eq. (12)-(14), Song et al. 2023; private to libmapfuse/src/fusion):
/// point-to-line (eq. (13)) or point-to-plane (eq. (14)) distance between a point of LSM A and a
/// point of LSM B, both in their anchor keyframes' body frames. `ElementResidual` is the
/// templated (autodiff) form, the reference; `ElementCost` evaluates the same residual with
/// closed-form Jacobians (GBA evaluates it for every associated point in every iteration).
#include <ceres/ceres.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mapfuse::fusion::detail {

/// d = (R_a p_a + t_a) - (R_b q_b + t_b), u = R_b dir_b (line direction or plane normal);
/// line: r = (I - u u^T) d / sigma; plane: r = (u^T d / sigma, 0, 0).
struct ElementResidual {
  Eigen::Vector3d pa, qb, dir_b;
  bool plane;
  double inv_sigma;
  template <class T>
  bool operator()(const T* ta, const T* qa, const T* tb, const T* qbq, T* res) const {
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> TA(ta), TB(tb);
    Eigen::Map<const Eigen::Quaternion<T>> QA(qa), QB(qbq);
    const Eigen::Matrix<T, 3, 1> d = QA * pa.cast<T>() + TA - (QB * qb.cast<T>() + TB);
    const Eigen::Matrix<T, 3, 1> u = QB * dir_b.cast<T>();
    if (plane) {
      res[0] = T(inv_sigma) * u.dot(d);
      res[1] = T(0);
      res[2] = T(0);
    } else {
      const Eigen::Matrix<T, 3, 1> perp = d - u * u.dot(d);
      for (int i = 0; i < 3; ++i) res[i] = T(inv_sigma) * perp[i];
    }
    return true;
  }
};

/// The same residual with analytic Jacobians. Rotations are perturbed on the left,
/// R <- Exp(delta) R, as ceres::EigenQuaternionManifold (and the yaw-only manifold) do: with
/// dd/dt_a = I, dd/dt_b = -I, dd/ddelta_a = -[R_a p_a]x, dd/ddelta_b = [R_b q_b]x and
/// du/ddelta_b = -[u]x, the Jacobian in the tangent space J_delta is mapped to the ambient
/// quaternion (x, y, z, w) as J_q = 4 J_delta P(q)^T, where P(q) = d(Exp(delta) q)/d delta at 0
/// satisfies P^T P = I / 4: Ceres' product J_q P then gives back J_delta.
class ElementCost final : public ceres::SizedCostFunction<3, 3, 4, 3, 4> {
 public:
  explicit ElementCost(const ElementResidual& r) : r_(r) {}

  bool Evaluate(const double* const* x, double* residuals, double** jacobians) const override {
    using Eigen::Matrix3d;
    using Eigen::Vector3d;
    const Eigen::Map<const Vector3d> ta(x[0]), tb(x[2]);
    const Eigen::Map<const Eigen::Quaterniond> qa(x[1]), qb(x[3]);
    const Vector3d pa_w = qa * r_.pa, qb_w = qb * r_.qb;
    const Vector3d d = pa_w + ta - qb_w - tb;
    const Vector3d u = qb * r_.dir_b;
    const double s = r_.inv_sigma, ud = u.dot(d);
    Eigen::Map<Vector3d> res(residuals);
    Matrix3d M;  // dr/dd (rows beyond the first are zero for a plane)
    Matrix3d N;  // dr/du
    if (r_.plane) {
      res << s * ud, 0, 0;
      M.setZero();
      M.row(0) = s * u.transpose();
      N.setZero();
      N.row(0) = s * d.transpose();
    } else {
      res = s * (d - u * ud);
      M = s * (Matrix3d::Identity() - u * u.transpose());
      N = -s * (ud * Matrix3d::Identity() + u * d.transpose());
    }
    if (jacobians == nullptr) return true;
    using J3 = Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;
    using J4 = Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>>;
    if (jacobians[0]) J3{jacobians[0]} = M;
    if (jacobians[2]) J3{jacobians[2]} = -M;
    if (jacobians[1]) J4{jacobians[1]} = -4.0 * M * skew(pa_w) * plusJacobian(qa).transpose();
    if (jacobians[3])
      J4{jacobians[3]} = 4.0 * (M * skew(qb_w) - N * skew(u)) * plusJacobian(qb).transpose();
    return true;
  }

 private:
  static Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
    Eigen::Matrix3d S;
    S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return S;
  }
  /// d(Exp(delta) q)/d delta at delta = 0, rows x, y, z, w: 0.5 [w I - [v]x ; -v^T].
  static Eigen::Matrix<double, 4, 3> plusJacobian(const Eigen::Quaterniond& q) {
    Eigen::Matrix<double, 4, 3> P;
    P.topRows<3>() = 0.5 * (q.w() * Eigen::Matrix3d::Identity() - skew(q.vec()));
    P.row(3) = -0.5 * q.vec().transpose();
    return P;
  }
  ElementResidual r_;
};

}  // namespace mapfuse::fusion::detail
