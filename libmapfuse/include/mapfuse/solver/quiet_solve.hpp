#pragma once
/// @file One small Ceres problem solved quietly: Levenberg-Marquardt (Ceres' default trust
/// region), one thread (the callers run in parallel over keyframes, tracks or drives), nothing
/// logged. The settings the localizer, the drive smoother and the aerial triangulation share;
/// Ceres stays out of this header (callers include <ceres/ceres.h> to build their problem).

namespace ceres {
class Problem;
}  // namespace ceres

namespace mapfuse::solver {

/// The linear solver of each Levenberg-Marquardt step.
enum class LinearSolver {
  kDenseQr,               ///< a few parameters (one pose, one point)
  kSparseNormalCholesky,  ///< many parameter blocks (a drive's keyframes)
};

struct QuietSolveResult {
  int iterations = 0;       ///< Levenberg-Marquardt iterations (Ceres' summary.iterations)
  bool converged = false;   ///< Ceres' termination type is CONVERGENCE
  double final_cost = 0.0;  ///< Ceres convention: sum of rho(|r|^2) / 2
};

/// @brief Minimises `problem` in place (its parameter blocks hold the result).
QuietSolveResult solveQuietly(ceres::Problem& problem, LinearSolver linear_solver,
                              int max_iterations);

}  // namespace mapfuse::solver
