#include "mapfuse/sim/drive_statistics.hpp"

#include <cmath>

namespace mapfuse::sim {

void DriveStatistics::add(const Drive& d, const std::vector<std::size_t>& kf,
                          const DriveParams& P) {
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

void DriveStatistics::add(const DriveStatistics& s) {
  km += s.km;
  gps_fixes += s.gps_fixes;
  gps_outliers += s.gps_outliers;
  gps_inliers += s.gps_inliers;
  gps_sq_sum += s.gps_sq_sum;
  gps_stamp_sum += s.gps_stamp_sum;
  drift_windows += s.drift_windows;
  drift_sq_sum += s.drift_sq_sum;
  drift_expected_sq_sum += s.drift_expected_sq_sum;
}

double DriveStatistics::gpsErrorRms() const {
  return gps_inliers ? std::sqrt(gps_sq_sum / gps_inliers) : 0.0;
}

double DriveStatistics::gpsErrorRmsExpected(const DriveParams& P) const {
  const double a = P.gps_bias_min, b = P.gps_bias_max;
  const double mean_t = gps_inliers ? gps_stamp_sum / gps_inliers : 0.0;
  // E|b|^2 of a magnitude uniform in [a, b], plus 2 axes of white noise and of the random walk.
  return std::sqrt((a * a + a * b + b * b) / 3.0 + 2 * P.gps_white_sigma * P.gps_white_sigma +
                   2 * P.gps_bias_walk * P.gps_bias_walk * mean_t);
}

double DriveStatistics::driftRms() const {
  return drift_windows ? std::sqrt(drift_sq_sum / drift_windows) : 0.0;
}

double DriveStatistics::driftRmsExpected() const {
  return drift_windows ? std::sqrt(drift_expected_sq_sum / drift_windows) : 0.0;
}

}  // namespace mapfuse::sim
