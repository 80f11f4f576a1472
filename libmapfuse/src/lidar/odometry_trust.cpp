#include "mapfuse/lidar/odometry_trust.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

#include "mapfuse/core/error.hpp"

namespace mapfuse::lidar {
namespace {
constexpr double kDeg = 180.0 / M_PI;

double angleDeg(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(R).angle() * kDeg;
}

void addReason(std::string& r, const char* fmt, double a, double b) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  if (!r.empty()) r += "; ";
  r += buf;
}
}  // namespace

double translationConstraint(const LocalVoxelMap& map, const std::vector<Eigen::Vector3d>& source,
                             const Pose3& T, double max_distance, int stride) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  int n = 0;
  MapNeighbor nb;
  const double max_d2 = max_distance * max_distance;
  for (std::size_t i = 0; i < source.size(); i += static_cast<std::size_t>(std::max(1, stride))) {
    if (!map.nearest(T * source[i], max_d2, &nb)) continue;
    if (nb.normal.squaredNorm() < 0.5) continue;
    const Eigen::Vector3d& nrm = nb.normal;
    A += nrm * nrm.transpose();
    ++n;
  }
  if (n == 0) return 0.0;
  A /= n;
  return std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(A).eigenvalues()(0));
}

StepAssessment assessStep(const MapRegistrationResult& reg, const Pose3& T_prev,
                          const Pose3* T_pred, double dt, double constraint,
                          const TrustSettings& s) {
  StepAssessment a;
  const Pose3& T = reg.T_map_scan;
  const Pose3 step = T_prev.inverse() * T;
  a.speed = step.translation().norm() / dt;
  a.rotation_rate = angleDeg(step.linear()) / dt;
  if (T_pred) {
    const Pose3 dev = T_pred->inverse() * T;
    a.deviation_m = dev.translation().norm();
    a.deviation_deg = angleDeg(dev.linear());
  }
  a.constraint = constraint;
  std::string& r = a.reasons;
  if (!reg.converged)
    addReason(r, "registration did not converge in %.0f iterations", reg.iterations, 0);
  if (reg.inlier_share < s.min_inlier_share)
    addReason(r, "inlier share %.2f < %.2f", reg.inlier_share, s.min_inlier_share);
  if (constraint < s.min_constraint)
    addReason(r, "degenerate: translation constraint %.3f < %.3f", constraint, s.min_constraint);
  if (a.speed > s.max_speed) addReason(r, "speed %.1f m/s > %.1f", a.speed, s.max_speed);
  if (a.rotation_rate > s.max_rotation_rate)
    addReason(r, "rotation rate %.1f deg/s > %.1f", a.rotation_rate, s.max_rotation_rate);
  // A velocity change of a over dt moves the pose a * dt^2 away from the prediction.
  const double max_dev_m = std::max(s.max_deviation_floor, s.max_acceleration * dt * dt);
  const double max_dev_deg = std::max(s.max_deviation_floor, s.max_angular_acceleration * dt * dt);
  if (a.deviation_m > max_dev_m)
    addReason(r, "%.2f m from the constant-velocity prediction > %.2f", a.deviation_m, max_dev_m);
  if (a.deviation_deg > max_dev_deg)
    addReason(r, "%.2f deg from the constant-velocity prediction > %.2f", a.deviation_deg,
              max_dev_deg);
  a.trusted = r.empty();
  return a;
}

}  // namespace mapfuse::lidar
