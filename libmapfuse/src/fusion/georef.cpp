#include "mapfuse/fusion/georef.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "factors.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/parallel_for.hpp"
#include "mapfuse/geo/track_agreement.hpp"

namespace mapfuse::fusion {

using detail::PoseParams;

Matrix6d relativeOdometryCovariance(const Keyframe& a, const Keyframe& b, double sigma_t_per_m,
                                    double sigma_r_per_m, double min_sigma_t, double min_sigma_r) {
  const double dist = (b.T_frame_body.translation() - a.T_frame_body.translation()).norm();
  const double st = std::max(min_sigma_t, sigma_t_per_m * dist);
  const double sr = std::max(min_sigma_r, sigma_r_per_m * dist);
  Matrix6d cov = diagonalCovariance(st, sr);
  // The growth of the keyframes' absolute standard deviations between a and b bounds the drift
  // between them. Odometry drift is systematic (a wheel scale error, a gyro bias: the error grows
  // linearly along the drive), so the relative sigma is the difference of the sigmas. The
  // difference of the variances (a random walk's increment) grows with the absolute sigma itself:
  // late in a 20 km drive it made consecutive keyframes 5 m apart in sigma, and georef bent the
  // odometry to the GPS noise (relative error 1.1 m per 16 m against the input's 0.08 m).
  for (int i = 0; i < 6; ++i) {
    const double growth =
        std::sqrt(std::max(0.0, b.covariance(i, i))) - std::sqrt(std::max(0.0, a.covariance(i, i)));
    cov(i, i) = std::max(cov(i, i), growth * growth);
  }
  return cov;
}

namespace {

struct GpsObs {
  int index;            // into lsm.gps
  int kf_a, kf_b;       // keyframe interval (first/last pair at the ends)
  double alpha;         // interpolation weight of kf_b
  Eigen::Vector3d enu;  // measured position
  Eigen::Matrix3d sqrt_info;
  bool rejected = false;
};

/// Odometry against the fused keyframes (issue 33, geo/track_agreement.hpp): the slope of the
/// height difference over odometry distance (a tilted dead reckoning climbs or sinks steadily)
/// and the median chord scale over geo::kScaleWindow m, minus 1 (a wheel scale error).
void odometryAgreement(const std::vector<Keyframe>& kfs, GeorefResult& res) {
  std::vector<Eigen::Vector3d> odom, fused;
  for (std::size_t i = 0; i < kfs.size(); ++i) {
    odom.push_back(kfs[i].T_frame_body.translation());
    fused.push_back(res.lsm.keyframes[i].T_frame_body.translation());
  }
  const geo::TrackAgreement a = geo::trackAgreement(odom, fused, geo::kScaleWindow);
  res.odom_vertical_slope = a.vertical_slope;
  res.odom_scale_error = a.scale_error;
}

}  // namespace

namespace {

/// Each fix with the keyframe interval around its (offset-corrected) stamp; fixes beyond
/// gps_max_extrapolation of the keyframes' span are dropped (counted).
std::vector<GpsObs> associateFixes(const Lsm& lsm, const geo::EnuConverter& enu,
                                   const GeorefSettings& s, const std::string& source,
                                   GeorefResult& res) {
  const auto& kfs = lsm.keyframes;
  const int nk = int(kfs.size());
  std::vector<GpsObs> obs;
  for (int g = 0; g < int(lsm.gps.size()); ++g) {
    const GpsFix& fix = lsm.gps[g];
    const double t = fix.stamp + s.gps_time_offset;
    GpsObs o{g, 0, 1, 0.0, enu.toEnu(fix.position), Eigen::Matrix3d::Identity()};
    if (t <= kfs.front().stamp) {
      if (kfs.front().stamp - t > s.gps_max_extrapolation) {
        ++res.gps_dropped;
        continue;
      }
    } else if (t >= kfs.back().stamp) {
      if (t - kfs.back().stamp > s.gps_max_extrapolation) {
        ++res.gps_dropped;
        continue;
      }
      o.kf_a = nk - 2;
      o.kf_b = nk - 1;
      o.alpha = 1.0;
    } else {
      const auto it = std::upper_bound(kfs.begin(), kfs.end(), t,
                                       [](double v, const Keyframe& k) { return v < k.stamp; });
      o.kf_b = int(it - kfs.begin());
      o.kf_a = o.kf_b - 1;
      const double dt = kfs[o.kf_b].stamp - kfs[o.kf_a].stamp;
      o.alpha = dt > 0 ? (t - kfs[o.kf_a].stamp) / dt : 0.0;
    }
    if (!(fix.sigma_h > 0) || !(fix.sigma_v > 0))
      throw InputError(source + ": gps[" + std::to_string(g) + "] has a non-positive sigma");
    o.sqrt_info = Eigen::Vector3d(1 / fix.sigma_h, 1 / fix.sigma_h, 1 / fix.sigma_v).asDiagonal();
    obs.push_back(o);
  }
  if (obs.empty()) throw InputError(source + ": no GPS fix within the keyframe time span");
  return obs;
}

/// Initial T_enu_odom: yaw + translation fit of the odometry onto the fixes, refitted on the
/// inliers of the first fit (residual within 3x the median, at least 3 sigma_h).
Pose3 initialAlignment(const Lsm& lsm, const std::vector<GpsObs>& obs) {
  const auto& kfs = lsm.keyframes;
  std::vector<Eigen::Vector3d> po, pg;
  for (const auto& o : obs) {
    po.push_back(
        interpolate(kfs[o.kf_a].T_frame_body, kfs[o.kf_b].T_frame_body, o.alpha).translation());
    pg.push_back(o.enu);
  }
  std::vector<char> use(obs.size(), 1);
  Pose3 T_enu_odom = geo::fitYawTranslation(po, pg, use);
  std::vector<double> r;
  for (std::size_t k = 0; k < po.size(); ++k) r.push_back((T_enu_odom * po[k] - pg[k]).norm());
  std::vector<double> sorted = r;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double gate = std::max(3.0 * sorted[sorted.size() / 2], 3.0 * lsm.gps[0].sigma_h);
  for (std::size_t k = 0; k < r.size(); ++k) use[k] = r[k] <= gate;
  return geo::fitYawTranslation(po, pg, use);
}

/// A fix's position on the fused keyframes (interpolated between its two).
Eigen::Vector3d fixOnPoses(const GpsObs& o, const std::vector<PoseParams>& poses) {
  return (1 - o.alpha) * Eigen::Map<const Eigen::Vector3d>(poses[o.kf_a].t) +
         o.alpha * Eigen::Map<const Eigen::Vector3d>(poses[o.kf_b].t);
}

/// Eq. (4): the keyframes minimising the odometry terms (eq. 5, fixed from the input) plus the
/// GPS terms (eq. 6) and a tilt prior per keyframe; Cauchy-robust in the first round, then
/// fixes above chi2_gate rejected and the graph re-solved (up to max_rejection_rounds).
void solvePoseGraph(const std::vector<Keyframe>& kfs, const GeorefSettings& s,
                    std::vector<PoseParams>& poses, std::vector<GpsObs>& obs, GeorefResult& res) {
  const int nk = int(kfs.size());
  std::vector<Pose3> rel(nk);
  std::vector<Matrix6d> rel_L(nk);
  for (int i = 0; i + 1 < nk; ++i) {
    rel[i] = kfs[i].T_frame_body.inverse() * kfs[i + 1].T_frame_body;
    rel_L[i] = detail::sqrtInformation<6>(relativeOdometryCovariance(
        kfs[i], kfs[i + 1], s.odom_sigma_translation_per_m, s.odom_sigma_rotation_per_m,
        s.odom_min_sigma_translation, s.odom_min_sigma_rotation));
  }
  for (int round = 0; round < std::max(1, s.max_rejection_rounds); ++round) {
    ceres::Problem problem;
    for (auto& p : poses) detail::addPose(problem, p);
    for (int i = 0; i + 1 < nk; ++i)  // eq. (5)
      problem.AddResidualBlock(detail::RelativePoseFactor::create(rel[i], rel_L[i]), nullptr,
                               poses[i].t, poses[i].q, poses[i + 1].t, poses[i + 1].q);
    // Tilt from the odometry (its z is up), the same assumption as the yaw-only initial fit.
    if (s.gravity_sigma > 0)
      for (int i = 0; i < nk; ++i)
        problem.AddResidualBlock(
            detail::GravityFactor::create(
                kfs[i].T_frame_body.linear().transpose() * Eigen::Vector3d::UnitZ(),
                s.gravity_sigma),
            nullptr, poses[i].q);
    // eq. (6): GPS position factors, Cauchy-robust in the first round.
    int active = 0;
    for (const auto& o : obs) {
      if (o.rejected) continue;
      ++active;
      ceres::LossFunction* loss = round == 0 ? new ceres::CauchyLoss(s.cauchy_scale) : nullptr;
      problem.AddResidualBlock(
          detail::InterpolatedPositionFactor::create(o.enu, o.alpha, o.sqrt_info), loss,
          poses[o.kf_a].t, poses[o.kf_b].t);
    }
    if (active < 2) {  // a single fix fixes position only: hold the initial heading
      problem.SetParameterBlockConstant(poses[0].q);
    }
    ceres::Solver::Options opt;
    opt.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    opt.max_num_iterations = s.max_iterations;
    opt.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(opt, &problem, &summary);
    res.iterations += int(summary.iterations.size());
    res.converged = summary.termination_type == ceres::CONVERGENCE;
    res.final_cost = summary.final_cost;

    // chi-square gate on whitened residuals of the still-active fixes
    int newly = 0;
    for (auto& o : obs) {
      if (o.rejected) continue;
      const double chi2 = (o.sqrt_info * (fixOnPoses(o, poses) - o.enu)).squaredNorm();
      if (chi2 > s.chi2_gate && active - newly > 2) {
        o.rejected = true;
        ++newly;
      }
    }
    if (newly == 0 && round > 0) break;
  }
}

/// Residual statistics over the accepted fixes (horizontal, vertical, signed vertical mean);
/// the rejected ones counted with their stamps.
void residualStatistics(const Lsm& lsm, const std::vector<GpsObs>& obs,
                        const std::vector<PoseParams>& poses, GeorefResult& res) {
  std::vector<double> r;
  double h_sq = 0, v_sq = 0, v_sum = 0;  // per axis: horizontal and vertical (signed)
  for (const auto& o : obs) {
    if (o.rejected) {
      ++res.gps_rejected;
      res.rejected_stamps.push_back(lsm.gps[o.index].stamp);
    } else {
      const Eigen::Vector3d d = fixOnPoses(o, poses) - o.enu;
      r.push_back(d.norm());
      h_sq += d.head<2>().squaredNorm(), v_sq += d.z() * d.z(), v_sum += d.z();
    }
  }
  res.gps_used = int(r.size());
  double sum = 0, sq = 0;
  for (double v : r) sum += v, sq += v * v, res.residual_max = std::max(res.residual_max, v);
  if (!r.empty()) {
    const double n_r = double(r.size());
    res.residual_mean = sum / n_r, res.residual_rms = std::sqrt(sq / n_r);
    res.residual_h_rms = std::sqrt(h_sq / n_r), res.residual_v_rms = std::sqrt(v_sq / n_r);
    res.residual_v_mean = v_sum / n_r;
  }
}

/// The LSM in enu with the fused keyframes: GPS-level position, odometry-level attitude sigma.
void writeFusedKeyframes(const Lsm& lsm, const geo::GeoOrigin& origin,
                         const std::vector<PoseParams>& poses, GeorefResult& res) {
  const int nk = int(lsm.keyframes.size());
  res.lsm = lsm;
  res.lsm.frame = LsmFrame::kEnu;
  res.lsm.origin = origin;
  for (int i = 0; i < nk; ++i) {
    Keyframe& k = res.lsm.keyframes[i];
    k.T_frame_body = poses[i].get();
    const double sh = lsm.gps.front().sigma_h / std::sqrt(std::max(1.0, double(res.gps_used) / nk));
    Matrix6d cov = Matrix6d::Zero();
    cov.diagonal() << sh * sh, sh * sh, 4 * sh * sh,
        lsm.keyframes[i].covariance.diagonal().tail<3>();
    k.covariance = cov;
  }
}

/// Trust (docs/fusion.md): odometry that disagrees with GPS leaves residuals above its noise,
/// many fixes rejected, or a height slope / scale against the fused keyframes.
bool trusted(const Lsm& lsm, const GeorefResult& res, const GeorefSettings& s) {
  const double sigma_h = lsm.gps.front().sigma_h, sigma_v = lsm.gps.front().sigma_v;
  const int judged = res.gps_rejected + res.gps_used;
  const double rejected_share = judged == 0 ? 0.0 : double(res.gps_rejected) / double(judged);
  return res.residual_h_rms <= s.trust_sigma_ratio * sigma_h &&
         res.residual_v_rms <= s.trust_sigma_ratio * sigma_v &&
         rejected_share <= s.trust_max_rejected_share &&
         std::abs(res.odom_vertical_slope) <= s.trust_max_vertical_slope &&
         std::abs(res.odom_scale_error) <= s.trust_max_scale_error;
}

}  // namespace

GeorefResult georeferenceLsm(const Lsm& lsm, const geo::GeoOrigin& origin, const GeorefSettings& s,
                             const std::string& source) {
  if (lsm.keyframes.size() < 2)
    throw InputError(source + ": georef needs at least 2 keyframes, the LSM has " +
                     std::to_string(lsm.keyframes.size()));
  GeorefResult res;
  res.gps_total = int(lsm.gps.size());
  std::vector<GpsObs> obs = associateFixes(lsm, geo::EnuConverter(origin), s, source, res);
  const Pose3 T_enu_odom = initialAlignment(lsm, obs);
  std::vector<PoseParams> poses(lsm.keyframes.size());
  for (std::size_t i = 0; i < poses.size(); ++i)
    poses[i].set(T_enu_odom * lsm.keyframes[i].T_frame_body);
  solvePoseGraph(lsm.keyframes, s, poses, obs, res);  // eq. (4)
  residualStatistics(lsm, obs, poses, res);
  writeFusedKeyframes(lsm, origin, poses, res);
  odometryAgreement(lsm.keyframes, res);
  res.trusted = trusted(lsm, res, s);
  return res;
}

std::vector<GeorefResult> georeferenceLsms(const std::vector<Lsm>& lsms,
                                           const geo::GeoOrigin& origin,
                                           const GeorefSettings& settings,
                                           const std::vector<std::string>& sources, int threads) {
  using Clock = std::chrono::steady_clock;
  const int n = int(lsms.size());
  std::vector<GeorefResult> results(n);
  // One thread per input at most: a per-drive batch job (one LSM) must not start and spin an
  // idle OpenMP worker (it doubled the CPU time of such jobs).
  parallelFor(
      std::size_t(n),
      [&](std::size_t i) {
        const auto t = Clock::now();
        results[i] = georeferenceLsm(lsms[i], origin, settings, sources[i]);
        results[i].seconds = std::chrono::duration<double>(Clock::now() - t).count();
      },
      std::max(1, std::min(threads, n)));
  return results;
}

}  // namespace mapfuse::fusion
