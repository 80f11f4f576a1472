#include "mapfuse/localize/localizer.hpp"

#include <chrono>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "matching.hpp"
#include "pose_solver.hpp"

namespace mapfuse::localize {
namespace {

using detail::corrected;
using detail::matchPoints;
using detail::WorldPoint;
using detail::yawOf;

/// The window's observed points in ENU: each keyframe's points placed by the drive's relative
/// poses (prior_k^-1 prior_j), then by the current pose of keyframe k.
std::vector<WorldPoint> windowPoints(const DriveObservations& d, const std::vector<double>& dist,
                                     std::size_t k, const Pose3& T_current,
                                     const LocalizeSettings& s) {
  const double window = s.window;
  std::vector<WorldPoint> out;
  const Pose3 T_prior_inv = d.T_enu_body_prior[k].inverse();
  std::size_t j0 = k;
  while (j0 > 0 && dist[k] - dist[j0 - 1] <= window) --j0;
  for (std::size_t j = j0; j < d.points.size() && dist[j] - dist[k] <= window; ++j) {
    const Pose3 T = T_current * T_prior_inv * d.T_enu_body_prior[j];
    const Eigen::Matrix3d& R = T.linear();
    // the relative pose of j seen from k is uncertain in proportion to the distance between them
    const double sr = s.window_sigma_per_m * std::abs(dist[j] - dist[k]);
    const Eigen::Matrix2d relative = sr * sr * Eigen::Matrix2d::Identity();
    for (const auto& p : d.points[j])
      out.push_back(
          {&p, (T * p.p_body).head<2>(),
           Eigen::Matrix2d((R * p.cov_body * R.transpose()).topLeftCorner<2, 2>()) + relative});
  }
  return out;
}

/// Acquisition: the shift on a grid of +-radius that brings most points onto the map (each point
/// scores 1 - (d / tol)^2 within tol of its nearest target).
Eigen::Vector2d searchShift(const MapIndex& map, const std::vector<WorldPoint>& pts,
                            const LocalizeSettings& s) {
  const double tol = s.final_match_radius;
  const int n = static_cast<int>(std::floor(s.search_radius / s.search_step + 1e-9));
  Eigen::Vector2d best = Eigen::Vector2d::Zero();
  double best_score = -1;
  for (int ix = -n; ix <= n; ++ix)
    for (int iy = -n; iy <= n; ++iy) {
      const Eigen::Vector2d shift(ix * s.search_step, iy * s.search_step);
      double score = 0;
      for (const auto& wp : pts) {
        const TargetMatch m = map.nearest(wp.obs->key, wp.q + shift, tol);
        if (m.target) score += 1.0 - (m.distance / tol) * (m.distance / tol);
      }
      // ties (straight roads) go to the smaller shift
      score -= 1e-3 * shift.squaredNorm();
      if (score > best_score) best_score = score, best = shift;
    }
  return best;
}

Eigen::Matrix3d covOf(const Element& e, std::size_t i) {
  return i < e.covariances.size() ? e.covariances[i] : Eigen::Matrix3d::Zero();
}

Eigen::Matrix3d sqrtInformation(const Eigen::Matrix3d& cov) {
  return cov.inverse().llt().matrixL().transpose();
}

}  // namespace

const char* statusName(KeyframeStatus s) {
  return s == KeyframeStatus::kOk ? "ok" : "lost";
}

DriveObservations observationsOf(const Lsm& lsm, bool use_attributes, const std::string& source) {
  if (lsm.frame != LsmFrame::kEnu || !lsm.origin)
    throw InputError(source + ": frame must be enu (run georef first)");
  DriveObservations d;
  for (const auto& kf : lsm.keyframes) {
    d.ids.push_back(kf.id);
    d.stamps.push_back(kf.stamp);
    d.T_enu_body_prior.push_back(kf.T_frame_body);
  }
  d.points.resize(lsm.keyframes.size());
  for (const auto& e : lsm.elements) {
    if (e.points_body.empty()) continue;
    auto& out = d.points[lsm.keyframeIndex(e.anchor)];
    const int key = matchKey(e.cls, e.attributes, use_attributes);
    switch (geometryKind(e.cls)) {
      case GeometryKind::kLine:
        for (std::size_t i = 0; i < e.points_body.size(); ++i)
          out.push_back({key, true, e.points_body[i], covOf(e, i)});
        break;
      case GeometryKind::kPoint: out.push_back({key, false, e.points_body[0], covOf(e, 0)}); break;
      case GeometryKind::kPlanar: {  // the centre, with the mean point covariance (correlated)
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (std::size_t i = 0; i < e.points_body.size(); ++i) {
          c += e.points_body[i];
          cov += covOf(e, i);
        }
        const double n = double(e.points_body.size());
        out.push_back({key, false, c / n, cov / n});
        break;
      }
    }
  }
  return d;
}

LocalizeResult localizeDrive(const MapIndex& map, const DriveObservations& d,
                             const LocalizeSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  LocalizeResult result;
  const std::size_t n = d.T_enu_body_prior.size();
  std::vector<double> dist(n, 0.0);  // travelled distance along the prior poses
  for (std::size_t k = 1; k < n; ++k)
    dist[k] =
        dist[k - 1] +
        (d.T_enu_body_prior[k].translation() - d.T_enu_body_prior[k - 1].translation()).norm();
  std::optional<std::size_t> last_ok;  // last localised keyframe: the prediction's base
  Eigen::Matrix3d last_cov = Eigen::Matrix3d::Identity();  // its (x, y, yaw) covariance
  bool reacquire = true;  // first keyframe, or the previous one was lost
  const Eigen::Matrix3d gps_info =
      sqrtInformation(Eigen::Vector3d(s.prior_sigma * s.prior_sigma, s.prior_sigma * s.prior_sigma,
                                      s.prior_sigma_yaw * s.prior_sigma_yaw)
                          .asDiagonal());
  for (std::size_t k = 0; k < n; ++k) {
    KeyframeLocalization kl;
    kl.id = d.ids[k];
    kl.stamp = d.stamps[k];
    kl.distance = dist[k];
    kl.T_enu_prior = d.T_enu_body_prior[k];
    // Prediction: the last localised pose moved by the drive's own relative motion.
    Pose3 T = kl.T_enu_prior;
    detail::PlanarPrior motion;
    if (last_ok) {
      const std::size_t j = *last_ok;
      T = result.keyframes[j].T_enu_body * d.T_enu_body_prior[j].inverse() * kl.T_enu_prior;
      const double travelled = dist[k] - dist[j];
      motion.t = T.translation().head<2>();
      motion.yaw = yawOf(T);
      // eq. (L5): the last covariance carried over the motion (a heading error turns into a
      // position error across the displacement) plus the odometry's noise
      const Eigen::Vector2d delta =
          motion.t - result.keyframes[j].T_enu_body.translation().head<2>();
      Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
      F(0, 2) = -delta.y();
      F(1, 2) = delta.x();
      const double sm = s.motion_sigma + s.motion_sigma_per_m * travelled;
      const double sy = 1e-5 + s.motion_sigma_yaw_per_m * travelled;
      const Eigen::Matrix3d P =
          F * last_cov * F.transpose() +
          Eigen::Vector3d(sm * sm, sm * sm, sy * sy).asDiagonal().toDenseMatrix();
      motion.sqrt_info = sqrtInformation(P);
    }
    const Pose3 T_pred = T;
    std::vector<WorldPoint> pts = windowPoints(d, dist, k, T, s);
    kl.observed = static_cast<int>(pts.size());
    if (reacquire && !pts.empty()) {  // acquisition: no trusted prediction
      const Eigen::Vector2d shift = searchShift(map, pts, s);
      T.translation().head<2>() += shift;
      for (auto& wp : pts) wp.q += shift;
      kl.acquired = true;
      ++result.acquisitions;
    }
    detail::SolveInput in;
    in.robust_scale = s.robust_scale;
    in.max_iterations = s.max_solver_iterations;
    in.gps = {kl.T_enu_prior.translation().head<2>(), yawOf(kl.T_enu_prior), gps_info};
    if (last_ok) in.motion = motion;
    double sum_sq = 0;
    Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
    for (int r = 0; r < s.rounds; ++r) {
      const double a = s.rounds > 1 ? double(r) / double(s.rounds - 1) : 1.0;
      const double radius = s.match_radius + a * (s.final_match_radius - s.match_radius);
      in.c = T.translation().head<2>();
      in.yaw = yawOf(T);
      in.matches = matchPoints(map, pts, radius, s, &sum_sq);
      kl.matches = static_cast<int>(in.matches.size());
      if (kl.matches < s.min_matches) break;
      const detail::SolveOutput out = detail::solvePlanarCorrection(in);
      result.solver_iterations += out.iterations;
      information = out.information;
      T = corrected(T, out.x);
      for (auto& wp : pts) wp.q = detail::applyCorrection(out.x, in.c, wp.q);
    }
    if (kl.matches >= s.min_matches) {  // the residual after the last solve
      in.matches = matchPoints(map, pts, s.final_match_radius, s, &sum_sq);
      kl.matches = static_cast<int>(in.matches.size());
      kl.rms = in.matches.empty() ? 0.0 : std::sqrt(sum_sq / double(in.matches.size()));
    }
    if (kl.matches >= s.min_matches) {
      kl.T_enu_body = T;
      last_ok = k;
      last_cov = information.inverse();
      reacquire = false;
    } else {
      kl.status = KeyframeStatus::kLost;
      kl.T_enu_body = T_pred;
      ++result.lost;
      reacquire = true;  // the next keyframe searches around its prediction
    }
    result.keyframes.push_back(kl);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace mapfuse::localize
