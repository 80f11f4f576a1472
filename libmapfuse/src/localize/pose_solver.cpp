#include "pose_solver.hpp"

#include <ceres/ceres.h>

#include <cmath>

#include "mapfuse/solver/quiet_solve.hpp"
#include "residuals.hpp"

namespace mapfuse::localize::detail {
namespace {

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
  for (const Match& m : in.matches)
    problem.AddResidualBlock(MatchResidual::create(m, in.c), &loss, x);
  problem.AddResidualBlock(PriorResidual::create(in.c, in.yaw, in.gps), nullptr, x);
  if (in.motion)
    problem.AddResidualBlock(PriorResidual::create(in.c, in.yaw, *in.motion), nullptr, x);
  const solver::QuietSolveResult solved =
      solver::solveQuietly(problem, solver::LinearSolver::kDenseQr, in.max_iterations);
  SolveOutput out;
  out.x = Eigen::Vector3d(x[0], x[1], x[2]);
  out.iterations = solved.iterations;
  out.converged = solved.converged;
  out.information = informationAt(in, out.x);
  return out;
}

}  // namespace mapfuse::localize::detail
