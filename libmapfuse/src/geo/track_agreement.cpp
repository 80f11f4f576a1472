#include "mapfuse/geo/track_agreement.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace mapfuse::geo {

Pose3 fitYawTranslation(const std::vector<Eigen::Vector3d>& o,
                        const std::vector<Eigen::Vector3d>& g, const std::vector<char>& use) {
  Eigen::Vector3d mo = Eigen::Vector3d::Zero(), mg = Eigen::Vector3d::Zero();
  int n = 0;
  for (std::size_t k = 0; k < o.size(); ++k)
    if (use[k]) mo += o[k], mg += g[k], ++n;
  Pose3 T = Pose3::Identity();
  if (n == 0) return T;
  mo /= n;
  mg /= n;
  double sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < o.size(); ++k) {
    if (!use[k]) continue;
    const Eigen::Vector3d a = o[k] - mo, b = g[k] - mg;
    sxx += a.x() * b.x() + a.y() * b.y();
    sxy += a.x() * b.y() - a.y() * b.x();
  }
  const double yaw = (n >= 2 && std::hypot(sxx, sxy) > 1e-9) ? std::atan2(sxy, sxx) : 0.0;
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = mg - T.linear() * mo;
  return T;
}

TrackAgreement trackAgreement(const std::vector<Eigen::Vector3d>& odom,
                              const std::vector<Eigen::Vector3d>& ref, double scale_window) {
  TrackAgreement a;
  const std::size_t n = std::min(odom.size(), ref.size());
  a.samples = int(n);
  if (n == 0) return a;
  std::vector<double> dist(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) dist[i] = dist[i - 1] + (odom[i] - odom[i - 1]).norm();
  a.length = dist.back();
  // Vertical: the slope of the height difference over distance, and its spread about the mean.
  double ss = 0, sd = 0, sss = 0, ssd = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = (ref[i].z() - ref[0].z()) - (odom[i].z() - odom[0].z());
    ss += dist[i], sd += d, sss += dist[i] * dist[i], ssd += dist[i] * d;
  }
  const double var = double(n) * sss - ss * ss;
  a.vertical_slope = var > 1e-9 ? (double(n) * ssd - ss * sd) / var : 0.0;
  const double mean_d = sd / double(n);
  // Horizontal: residuals after the yaw + translation fit.
  const Pose3 T = fitYawTranslation(odom, ref, std::vector<char>(n, 1));
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d r = ref[i] - T * odom[i];
    a.horizontal_rms += r.head<2>().squaredNorm();
    const double dz = (ref[i].z() - ref[0].z()) - (odom[i].z() - odom[0].z()) - mean_d;
    a.vertical_rms += dz * dz;
  }
  a.horizontal_rms = std::sqrt(a.horizontal_rms / double(n));
  a.vertical_rms = std::sqrt(a.vertical_rms / double(n));
  // Scale: chords of scale_window m of odometry.
  std::vector<double> ratios;
  for (std::size_t i = 0, j = 0; i < n; ++i) {
    while (j < n && dist[j] - dist[i] < scale_window) ++j;
    if (j >= n) break;
    const double odo = (odom[j] - odom[i]).norm();
    if (odo > 0) ratios.push_back((ref[j] - ref[i]).norm() / odo);
  }
  if (ratios.empty()) return a;
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  a.scale_error = ratios[ratios.size() / 2] - 1.0;
  return a;
}

}  // namespace mapfuse::geo
