#include "mapfuse/solver/quiet_solve.hpp"

#include <ceres/ceres.h>

namespace mapfuse::solver {

QuietSolveResult solveQuietly(ceres::Problem& problem, LinearSolver linear_solver,
                              int max_iterations) {
  ceres::Solver::Options options;
  options.linear_solver_type =
      linear_solver == LinearSolver::kDenseQr ? ceres::DENSE_QR : ceres::SPARSE_NORMAL_CHOLESKY;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.max_num_iterations = max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  QuietSolveResult r;
  r.iterations = static_cast<int>(summary.iterations.size());
  r.converged = summary.termination_type == ceres::CONVERGENCE;
  r.final_cost = summary.final_cost;
  return r;
}

}  // namespace mapfuse::solver
