#include "mapfuse/vehicle/triangulation.hpp"

#include <ceres/ceres.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

#include "mapfuse/solver/quiet_solve.hpp"

namespace mapfuse::vehicle {
namespace {

/// Reprojection residual of one observation, in sigmas (eq. 3).
struct ReprojectionCost {
  ReprojectionCost(const Eigen::Matrix3d& K, const Pose3& T_cam_world, const Eigen::Vector2d& px,
                   double sigma)
      : K_(K), R_(T_cam_world.linear()), t_(T_cam_world.translation()), px_(px), sigma_(sigma) {}

  template <class T>
  bool operator()(const T* const p, T* residual) const {
    const Eigen::Matrix<T, 3, 1> P(p[0], p[1], p[2]);
    const Eigen::Matrix<T, 3, 1> c = R_.cast<T>() * P + t_.cast<T>();
    if (c.z() <= T(1e-6)) return false;
    const Eigen::Matrix<T, 3, 1> q = K_.cast<T>() * c;
    residual[0] = (q.x() / q.z() - T(px_.x())) / T(sigma_);
    residual[1] = (q.y() / q.z() - T(px_.y())) / T(sigma_);
    return true;
  }

  Eigen::Matrix3d K_, R_;
  Eigen::Vector3d t_;
  Eigen::Vector2d px_;
  double sigma_;
};

double maxParallax(const std::vector<TrackObservation>& obs, const Eigen::Vector3d& P) {
  double best = 0.0;
  for (std::size_t i = 0; i < obs.size(); ++i)
    for (std::size_t j = i + 1; j < obs.size(); ++j) {
      const Eigen::Vector3d a = (P - obs[i].T_world_cam.translation()).normalized();
      const Eigen::Vector3d b = (P - obs[j].T_world_cam.translation()).normalized();
      best = std::max(best, std::acos(std::clamp(a.dot(b), -1.0, 1.0)));
    }
  return best;
}

}  // namespace

Eigen::Vector3d triangulateLinear(const Eigen::Matrix3d& K,
                                  const std::vector<TrackObservation>& obs) {
  Eigen::MatrixXd A(2 * obs.size(), 4);
  for (std::size_t i = 0; i < obs.size(); ++i) {
    const Pose3 T_cam_world = obs[i].T_world_cam.inverse();
    Eigen::Matrix<double, 3, 4> P;
    P.leftCols<3>() = T_cam_world.linear();
    P.col(3) = T_cam_world.translation();
    P = K * P;
    A.row(2 * i) = obs[i].pixel.x() * P.row(2) - P.row(0);
    A.row(2 * i + 1) = obs[i].pixel.y() * P.row(2) - P.row(1);
  }
  for (int r = 0; r < A.rows(); ++r) A.row(r).normalize();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (std::abs(X(3)) < 1e-12) return X.head<3>() * 1e9;
  return X.head<3>() / X(3);
}

TriangulationResult triangulateTrack(const Eigen::Matrix3d& K,
                                     const std::vector<TrackObservation>& obs,
                                     const TriangulationSettings& s) {
  TriangulationResult r;
  if (int(obs.size()) < std::max(2, s.min_observations)) {
    r.reason = "observations";
    return r;
  }
  Eigen::Vector3d P = triangulateLinear(K, obs);
  r.parallax = maxParallax(obs, P);
  if (!P.allFinite() || r.parallax < s.min_parallax) {
    r.reason = "parallax";
    return r;
  }
  for (const auto& o : obs)
    if ((o.T_world_cam.inverse() * P).z() <= 0.0) {
      r.reason = "behind camera";
      return r;
    }

  ceres::Problem problem;
  double p[3] = {P.x(), P.y(), P.z()};
  for (const auto& o : obs) {
    auto* cost = new ceres::AutoDiffCostFunction<ReprojectionCost, 2, 3>(
        new ReprojectionCost(K, o.T_world_cam.inverse(), o.pixel, s.sigma_pixel));
    problem.AddResidualBlock(cost, new ceres::HuberLoss(s.huber_delta), p);
  }
  const solver::QuietSolveResult solved =
      solver::solveQuietly(problem, solver::LinearSolver::kDenseQr, s.max_iterations);
  r.iterations = solved.iterations;
  r.converged = solved.converged;
  P = Eigen::Vector3d(p[0], p[1], p[2]);

  // Final RMS (pixels) and covariance from the Gauss-Newton normal matrix.
  Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
  double sq = 0.0;
  for (const auto& o : obs) {
    const Pose3 T = o.T_world_cam.inverse();
    const Eigen::Vector3d c = T * P;
    if (c.z() <= 1e-6) {
      r.reason = "behind camera";
      return r;
    }
    const Eigen::Vector3d q = K * c;
    sq += (Eigen::Vector2d(q.x() / q.z(), q.y() / q.z()) - o.pixel).squaredNorm();
    Eigen::Matrix<double, 2, 3> Jproj;
    Jproj << K(0, 0) / c.z(), 0, -K(0, 0) * c.x() / (c.z() * c.z()), 0, K(1, 1) / c.z(),
        -K(1, 1) * c.y() / (c.z() * c.z());
    const Eigen::Matrix<double, 2, 3> J = Jproj * T.linear();
    JtJ += J.transpose() * J;
  }
  r.rms = std::sqrt(sq / double(obs.size()));
  r.p_world = P;
  r.parallax = maxParallax(obs, P);
  r.covariance = JtJ.inverse() * s.sigma_pixel * s.sigma_pixel;
  if (!r.covariance.allFinite()) {
    r.reason = "degenerate";
    return r;
  }
  if (r.rms > s.max_reprojection_rms) {
    r.reason = "reprojection";
    return r;
  }
  // Seen only far away (the vehicle turned off before passing it): depth rests on a short
  // baseline at long range, and ego-motion errors, which the pixel covariance above does not
  // hold, bias it by metres.
  r.nearest_range = std::numeric_limits<double>::infinity();
  for (const auto& o : obs)
    r.nearest_range = std::min(r.nearest_range, (P - o.T_world_cam.translation()).norm());
  if (s.max_range > 0 && r.nearest_range > s.max_range) {
    r.reason = "range";
    return r;
  }
  r.ok = true;
  return r;
}

}  // namespace mapfuse::vehicle
