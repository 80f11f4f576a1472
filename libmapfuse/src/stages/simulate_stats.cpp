// Error statistics of simulated drives (docs/simulate.md "Summary"): measured GPS error and
// odometry drift next to the values the configured sigmas predict.
#include "mapfuse/stages/simulate_stats.hpp"

#include <cmath>

namespace mapfuse::stages {

void DriveStatistics::add(const sim::Drive& d, const std::vector<std::size_t>& kf,
                          const sim::DriveParams& P) {
  // GPS: horizontal error of the fixes that are not multipath outliers.
  for (const auto& g : d.gps) {
    ++gps_fixes;
    if (g.outlier) {
      ++gps_outliers;
      continue;
    }
    gps_sq_sum += g.error_enu.head<2>().squaredNorm();
    gps_stamp_sum += g.fix.stamp;
    ++gps_inliers;
  }
  // Odometry: relative translation error over windows of >= kDriftWindow m between keyframes.
  std::size_t b = 0;
  for (std::size_t a = 0; a < kf.size(); ++a) {
    while (b < kf.size() && d.distance[kf[b]] - d.distance[kf[a]] < kDriftWindow) ++b;
    if (b >= kf.size()) break;
    const double L = d.distance[kf[b]] - d.distance[kf[a]];
    const Eigen::Vector3d rel_odom = (d.odom[kf[a]].inverse() * d.odom[kf[b]]).translation();
    const Eigen::Vector3d rel_true = (d.truth[kf[a]].inverse() * d.truth[kf[b]]).translation();
    const double e = (rel_odom - rel_true).norm() * kDriftWindow / L;
    drift_sq_sum += e * e;
    // Expected squared drift over kDriftWindow at this drive's speed: scale error, gyro bias
    // (lateral L^2 b / 2v), gyro white noise (L^3 q^2 / 3v) and wheel-speed noise.
    const double Lw = kDriftWindow, v = d.speed;
    drift_expected_sq_sum += P.wheel_scale_sigma * P.wheel_scale_sigma * Lw * Lw +
                             std::pow(P.gyro_bias_sigma * Lw * Lw / (2 * v), 2) +
                             P.gyro_noise_density * P.gyro_noise_density * Lw * Lw * Lw / (3 * v) +
                             P.wheel_speed_noise * P.wheel_speed_noise * Lw / (v * P.wheel_rate);
    ++drift_windows;
  }
  km += d.length() / 1000.0;
}

nlohmann::json DriveStatistics::toJson(const sim::DriveParams& P) const {
  nlohmann::json j;
  j["km_driven"] = km;
  j["gps_fixes"] = gps_fixes;
  j["gps_outliers_injected"] = gps_outliers;
  const double a = P.gps_bias_min, b = P.gps_bias_max;
  const double mean_t = gps_inliers ? gps_stamp_sum / gps_inliers : 0.0;
  // E|b|^2 of a magnitude uniform in [a, b], plus 2 axes of white noise and of the random walk.
  const double expected =
      std::sqrt((a * a + a * b + b * b) / 3.0 + 2 * P.gps_white_sigma * P.gps_white_sigma +
                2 * P.gps_bias_walk * P.gps_bias_walk * mean_t);
  j["gps_error_rms_m"] = gps_inliers ? std::sqrt(gps_sq_sum / gps_inliers) : 0.0;
  j["gps_error_rms_expected_m"] = expected;
  j["odometry_drift_windows"] = drift_windows;
  j["odometry_drift_per_100m_rms_m"] =
      drift_windows ? std::sqrt(drift_sq_sum / drift_windows) : 0.0;
  j["odometry_drift_per_100m_expected_m"] =
      drift_windows ? std::sqrt(drift_expected_sq_sum / drift_windows) : 0.0;
  return j;
}

}  // namespace mapfuse::stages
