#include "mapfuse/localize/drive_smoother.hpp"

#include <ceres/ceres.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>

#include "mapfuse/solver/quiet_solve.hpp"
#include "matching.hpp"
#include "residuals.hpp"

namespace mapfuse::localize {
namespace {

using detail::corrected;
using detail::yawOf;

/// Keyframe k's own observed points in ENU at the pose T.
std::vector<detail::WorldPoint> ownPoints(const DriveObservations& d, std::size_t k,
                                          const Pose3& T) {
  std::vector<detail::WorldPoint> out;
  out.reserve(d.points[k].size());
  const Eigen::Matrix3d& R = T.linear();
  for (const auto& p : d.points[k])
    out.push_back({&p, (T * p.p_body).head<2>(),
                   Eigen::Matrix2d((R * p.cov_body * R.transpose()).topLeftCorner<2, 2>())});
  return out;
}

/// eq. (L6): the drive's relative motion from keyframe i to j (prior poses) with its
/// square-root information.
detail::MotionResidual motionBetween(const DriveObservations& d, std::size_t i, std::size_t j,
                                     const Pose3& Ti, const Pose3& Tj, const SmootherSettings& s) {
  const Pose3& Pi = d.T_enu_body_prior[i];
  const Pose3& Pj = d.T_enu_body_prior[j];
  const double yi = yawOf(Pi);
  const Eigen::Vector2d dt = (Pj.translation() - Pi.translation()).head<2>();
  const double len = dt.norm();
  const double st = s.odometry_sigma + s.odometry_sigma_per_m * len;
  const double sy = 1e-5 + s.odometry_sigma_yaw_per_m * len;
  detail::MotionResidual r;
  r.ci = Ti.translation().head<2>();
  r.cj = Tj.translation().head<2>();
  r.yaw_i = yawOf(Ti);
  r.yaw_j = yawOf(Tj);
  r.t_ij = Eigen::Rotation2Dd(-yi) * dt;
  r.yaw_ij = detail::wrapAngle(yawOf(Pj) - yi);
  r.L = Eigen::Vector3d(1 / st, 1 / st, 1 / sy).asDiagonal();
  return r;
}

}  // namespace

void smoothDrive(const MapIndex& map, const DriveObservations& d, const LocalizeSettings& s,
                 const SmootherSettings& sm, LocalizeResult& result) {
  const std::size_t n = result.keyframes.size();
  if (n == 0) return;
  const auto t0 = std::chrono::steady_clock::now();
  const detail::PlanarPrior gps_template{
      Eigen::Vector2d::Zero(), 0.0,
      Eigen::Vector3d(1 / s.prior_sigma, 1 / s.prior_sigma, 1 / s.prior_sigma_yaw).asDiagonal()};
  std::vector<Pose3> T(n);
  for (std::size_t k = 0; k < n; ++k) T[k] = result.keyframes[k].T_enu_body;
  std::vector<int> matched(n, 0);
  std::vector<double> sum_sq(n, 0.0);
  // eq. (L7): all keyframes' matches, GPS priors and relative motions in one problem
  for (int round = 0; round < sm.smoother_rounds; ++round) {
    std::vector<Eigen::Vector3d> x(n, Eigen::Vector3d::Zero());
    ceres::Problem::Options po;
    po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(po);
    ceres::CauchyLoss loss(s.robust_scale);  // residuals are in sigmas
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector2d c = T[k].translation().head<2>();
      const std::vector<detail::WorldPoint> pts = ownPoints(d, k, T[k]);
      const std::vector<detail::Match> matches =
          detail::matchPoints(map, pts, s.final_match_radius, s, &sum_sq[k]);
      matched[k] = static_cast<int>(matches.size());
      for (const auto& m : matches)
        problem.AddResidualBlock(detail::MatchResidual::create(m, c), &loss, x[k].data());
      detail::PlanarPrior gps = gps_template;  // eq. (L3), the georeferenced pose
      gps.t = d.T_enu_body_prior[k].translation().head<2>();
      gps.yaw = yawOf(d.T_enu_body_prior[k]);
      problem.AddResidualBlock(detail::PriorResidual::create(c, yawOf(T[k]), gps), nullptr,
                               x[k].data());
      if (k > 0)
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<detail::MotionResidual, 3, 3, 3>(
                new detail::MotionResidual(motionBetween(d, k - 1, k, T[k - 1], T[k], sm))),
            nullptr, x[k - 1].data(), x[k].data());
    }
    result.solver_iterations +=
        solver::solveQuietly(problem, solver::LinearSolver::kSparseNormalCholesky,
                             s.max_solver_iterations)
            .iterations;
    for (std::size_t k = 0; k < n; ++k) T[k] = corrected(T[k], x[k]);
  }
  for (std::size_t k = 0; k < n; ++k) {  // the residual at the final poses
    KeyframeLocalization& kl = result.keyframes[k];
    kl.T_enu_body = T[k];
    double ss = 0;
    const std::vector<detail::Match> matches =
        detail::matchPoints(map, ownPoints(d, k, T[k]), s.final_match_radius, s, &ss);
    kl.matches = static_cast<int>(matches.size());
    kl.rms = matches.empty() ? 0.0 : std::sqrt(ss / double(matches.size()));
  }
  result.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace mapfuse::localize
