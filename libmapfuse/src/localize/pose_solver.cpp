#include "pose_solver.hpp"

#include <ceres/ceres.h>

#include <cmath>

namespace mapfuse::localize::detail {
namespace {

double wrapAngle(double a) {
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
};

void addPrior(ceres::Problem& problem, const SolveInput& in, const PlanarPrior& p, double* x) {
  const Eigen::Vector2d d = in.c - p.t;
  auto* f = new ceres::AutoDiffCostFunction<PriorResidual, 3, 3>(
      new PriorResidual{Eigen::Vector3d(d.x(), d.y(), wrapAngle(in.yaw - p.yaw)), p.sqrt_info});
  problem.AddResidualBlock(f, nullptr, x);
}

/// Information of x at the solution: sum of w J^T J over the matches (w: the Cauchy weight of
/// the block's squared residual) plus the priors' L^T L.
Eigen::Matrix3d informationAt(const SolveInput& in, const Eigen::Vector3d& x) {
  Eigen::Matrix3d H = in.gps.sqrt_info.transpose() * in.gps.sqrt_info;
  if (in.motion) H += in.motion->sqrt_info.transpose() * in.motion->sqrt_info;
  const double a2 = in.robust_scale * in.robust_scale;
  for (const Match& m : in.matches) {
    const Eigen::Vector2d q = applyCorrection(x, in.c, m.q);
    const Eigen::Vector2d v = q - (in.c + x.head<2>());  // R(theta) (q - c)
    Eigen::Matrix<double, 2, 3> J;                       // d q' / d x
    J << 1, 0, -v.y(), 0, 1, v.x();
    if (m.is_line) {
      const Eigen::RowVector3d j = m.sqrt_info(0, 0) * (m.n.transpose() * J);
      const double r = m.sqrt_info(0, 0) * m.n.dot(q - m.a);
      H += j.transpose() * j / (1.0 + r * r / a2);
    } else {
      const Eigen::Matrix<double, 2, 3> j = m.sqrt_info * J;
      const double r2 = (m.sqrt_info * (q - m.a)).squaredNorm();
      H += j.transpose() * j / (1.0 + r2 / a2);
    }
  }
  return H;
}

}  // namespace

Eigen::Vector2d applyCorrection(const Eigen::Vector3d& x, const Eigen::Vector2d& c,
                                const Eigen::Vector2d& q) {
  return c + x.head<2>() + Eigen::Rotation2Dd(x.z()) * (q - c);
}

SolveOutput solvePlanarCorrection(const SolveInput& in) {
  double x[3] = {0, 0, 0};
  ceres::Problem::Options po;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::CauchyLoss loss(in.robust_scale);  // residuals are in sigmas
  for (const Match& m : in.matches) {
    ceres::CostFunction* f =
        m.is_line
            ? static_cast<ceres::CostFunction*>(
                  new ceres::AutoDiffCostFunction<MatchResidual, 1, 3>(new MatchResidual{m, in.c}))
            : new ceres::AutoDiffCostFunction<MatchResidual, 2, 3>(new MatchResidual{m, in.c});
    problem.AddResidualBlock(f, &loss, x);
  }
  addPrior(problem, in, in.gps, x);
  if (in.motion) addPrior(problem, in, *in.motion, x);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = in.max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  SolveOutput out;
  out.x = Eigen::Vector3d(x[0], x[1], x[2]);
  out.iterations = static_cast<int>(summary.iterations.size());
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.information = informationAt(in, out.x);
  return out;
}

}  // namespace mapfuse::localize::detail
