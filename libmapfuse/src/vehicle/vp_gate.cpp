#include "mapfuse/vehicle/vp_gate.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace mapfuse::vehicle {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  return v[mid];
}

/// The road's grade change over the path from frame i to frame j: z(s) = a s² + b s + c fitted
/// by least squares to the heights of the path (not the body's pitch, which the suspension
/// rocks by 0.01 rad at ~0.7 Hz: the body tilt, not the road), |2 a (s_j - s_i)|.
double gradeChange(const std::vector<Pose3>& T, const std::vector<double>& s, std::size_t i,
                   std::size_t j) {
  if (j < i + 3) return 0.0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  const double z0 = T[i].translation().z();
  for (std::size_t k = i; k <= j; ++k) {
    const double u = s[k] - s[i];
    const Eigen::Vector3d row(u * u, u, 1.0);
    A += row * row.transpose();
    b += row * (T[k].translation().z() - z0);
  }
  const Eigen::Vector3d coef = A.ldlt().solve(b);
  return std::abs(2.0 * coef(0) * (s[j] - s[i]));
}

}  // namespace

std::vector<LookAhead> lookAheadMotion(const std::vector<Pose3>& T, double distance) {
  const std::size_t n = T.size();
  std::vector<double> s(n, 0.0);  // path length
  for (std::size_t i = 1; i < n; ++i)
    s[i] = s[i - 1] + (T[i].translation() - T[i - 1].translation()).norm();
  std::vector<LookAhead> out(n);
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    j = std::max(j, i);
    while (j < n && s[j] - s[i] < distance) ++j;
    if (j >= n) continue;  // the drive ends within the look-ahead
    LookAhead& a = out[i];
    a.valid = true;
    const Eigen::Matrix3d Ri_t = T[i].linear().transpose();
    for (std::size_t k = i + 1; k <= j; ++k) {
      const Eigen::Vector3d x = Ri_t * T[k].linear().col(0);  // body k's forward axis in body i
      a.heading_change = std::max(a.heading_change, std::abs(std::atan2(x.y(), x.x())));
    }
    a.pitch_change = gradeChange(T, s, i, j);
    const Eigen::Vector3d chord = Ri_t * (T[j].translation() - T[i].translation());
    if (chord.norm() > 1e-9) a.direction_body = chord.normalized();
  }
  return out;
}

double azimuthDifference(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& n) {
  const Eigen::Vector3d pa = a - a.dot(n) * n, pb = b - b.dot(n) * n;
  return std::atan2(n.dot(pa.cross(pb)), pa.dot(pb));
}

VpCalibration gateVanishingPoints(const std::vector<std::optional<VanishingEstimate>>& est,
                                  const std::vector<LookAhead>& motion,
                                  const std::vector<Eigen::Vector3d>& normals_cam,
                                  const Eigen::Matrix3d& R_cam_body, const VanishingSettings& s) {
  const std::size_t n = est.size();
  VpCalibration out;
  out.corrections.assign(n, 0.0);
  // 1. Straight and even look-ahead; the azimuth of the VP against that of the motion.
  std::vector<std::optional<double>> azimuth(n);
  std::vector<double> offsets;
  for (std::size_t i = 0; i < n; ++i) {
    if (!est[i]) continue;
    ++out.estimates;
    if (!motion[i].valid) {
      ++out.rejected_no_look_ahead;
      continue;
    }
    if (motion[i].heading_change > s.max_heading_change) {
      ++out.rejected_curve;
      continue;
    }
    if (motion[i].pitch_change > s.max_pitch_change) {
      ++out.rejected_vertical_curve;
      continue;
    }
    const Eigen::Vector3d motion_cam = R_cam_body * motion[i].direction_body;
    azimuth[i] = azimuthDifference(motion_cam, est[i]->direction_cam, normals_cam[i]);
    offsets.push_back(*azimuth[i]);
  }
  // A constant mount yaw shifts every frame's difference alike: compare with the median.
  out.azimuth_offset = median(offsets);
  std::vector<std::optional<double>> accepted(n);
  std::vector<double> values;
  for (std::size_t i = 0; i < n; ++i) {
    if (!azimuth[i]) continue;
    if (std::abs(*azimuth[i] - out.azimuth_offset) > s.max_azimuth_error) {
      ++out.rejected_azimuth;
      continue;
    }
    accepted[i] = est[i]->pitch;
    values.push_back(est[i]->pitch);
  }
  // 2. Enough support, and a correction that stands out of its spread.
  out.accepted = int(values.size());
  out.median = median(values);
  std::vector<double> dev;
  for (double v : values) dev.push_back(std::abs(v - out.median));
  out.spread = 1.4826 * median(dev);
  out.standard_error =
      values.empty() ? 0.0 : 1.2533 * out.spread / std::sqrt(double(values.size()));
  if (out.accepted < s.min_frames) {
    out.fallback = true;
    out.fallback_reason = "too few frames";
  } else if (std::abs(out.median) < s.min_significance * out.standard_error) {
    out.fallback = true;
    out.fallback_reason = "not significant";
  }
  if (!out.fallback) out.corrections = smoothCorrections(accepted, s.window);
  return out;
}

}  // namespace mapfuse::vehicle
