#pragma once
/// @file The Ceres residuals of the localiser (private): a matched point after a planar
/// correction against its map target (eq. L1 + L2), a planar prior (eq. L3) and the drive's
/// relative motion between two keyframes (eq. L6). A correction x = (dx, dy, dtheta) acts on a
/// pose about its position c: q' = c + d + R(dtheta) (q - c) (docs/localize.md).
#include <ceres/ceres.h>

#include <Eigen/Core>
#include <cmath>

#include "pose_solver.hpp"

namespace mapfuse::localize::detail {

inline double wrapAngle(double a) {
  return std::atan2(std::sin(a), std::cos(a));
}

/// eq. (L1) + (L2): the matched point after the correction, against its target.
struct MatchResidual {
  Match m;
  Eigen::Vector2d c;

  template <class T>
  bool operator()(const T* x, T* r) const {
    const T cs = ceres::cos(x[2]), sn = ceres::sin(x[2]);
    const T dx = T(m.q.x() - c.x()), dy = T(m.q.y() - c.y());
    const T px = T(c.x()) + x[0] + cs * dx - sn * dy;
    const T py = T(c.y()) + x[1] + sn * dx + cs * dy;
    const T ex = px - T(m.a.x()), ey = py - T(m.a.y());
    if (m.is_line) {
      r[0] = T(m.sqrt_info(0, 0)) * (T(m.n.x()) * ex + T(m.n.y()) * ey);
    } else {
      r[0] = T(m.sqrt_info(0, 0)) * ex + T(m.sqrt_info(0, 1)) * ey;
      r[1] = T(m.sqrt_info(1, 0)) * ex + T(m.sqrt_info(1, 1)) * ey;
    }
    return true;
  }

  /// @brief The cost function of one match (1 residual for a line, 2 for a point).
  static ceres::CostFunction* create(const Match& m, const Eigen::Vector2d& c) {
    if (m.is_line)
      return new ceres::AutoDiffCostFunction<MatchResidual, 1, 3>(new MatchResidual{m, c});
    return new ceres::AutoDiffCostFunction<MatchResidual, 2, 3>(new MatchResidual{m, c});
  }
};

/// eq. (L3): a planar prior on the corrected pose (linear in x).
struct PriorResidual {
  Eigen::Vector3d offset;  ///< (c - t_prior, psi - psi_prior wrapped), m, m, rad
  Eigen::Matrix3d L;       ///< square-root information

  template <class T>
  bool operator()(const T* x, T* r) const {
    const Eigen::Matrix<T, 3, 1> e(T(offset.x()) + x[0], T(offset.y()) + x[1],
                                   T(offset.z()) + x[2]);
    Eigen::Map<Eigen::Matrix<T, 3, 1>> out(r);
    out = L.cast<T>() * e;
    return true;
  }

  /// @brief The prior `p` on the pose at (c, yaw) corrected by x.
  static ceres::CostFunction* create(const Eigen::Vector2d& c, double yaw, const PlanarPrior& p) {
    const Eigen::Vector2d d = c - p.t;
    return new ceres::AutoDiffCostFunction<PriorResidual, 3, 3>(
        new PriorResidual{Eigen::Vector3d(d.x(), d.y(), wrapAngle(yaw - p.yaw)), p.sqrt_info});
  }
};

/// eq. (L6): the relative motion of keyframe j seen from keyframe i after both corrections,
/// against the drive's own (t_ij in i's heading frame, psi_ij):
///   r = L ( R(-(psi_i + theta_i)) (c_j + d_j - c_i - d_i) - t_ij,  psi_j + theta_j - psi_i -
///   theta_i - psi_ij )
struct MotionResidual {
  Eigen::Vector2d ci, cj;  ///< current positions, m
  double yaw_i, yaw_j;     ///< current headings, rad
  Eigen::Vector2d t_ij;    ///< the drive's relative translation in i's heading frame, m
  double yaw_ij;           ///< the drive's relative heading, rad
  Eigen::Matrix3d L;       ///< square-root information of (t_ij, yaw_ij)

  template <class T>
  bool operator()(const T* xi, const T* xj, T* r) const {
    const T yi = T(yaw_i) + xi[2];
    const T ex = T(cj.x() - ci.x()) + xj[0] - xi[0], ey = T(cj.y() - ci.y()) + xj[1] - xi[1];
    const T cs = ceres::cos(yi), sn = ceres::sin(yi);
    // the heading difference is small between consecutive keyframes: wrap the constant part only
    const Eigen::Matrix<T, 3, 1> e(cs * ex + sn * ey - T(t_ij.x()),
                                   -sn * ex + cs * ey - T(t_ij.y()),
                                   T(wrapAngle(yaw_j - yaw_i - yaw_ij)) + xj[2] - xi[2]);
    Eigen::Map<Eigen::Matrix<T, 3, 1>> out(r);
    out = L.cast<T>() * e;
    return true;
  }
};

}  // namespace mapfuse::localize::detail
