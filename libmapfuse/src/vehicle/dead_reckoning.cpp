#include "mapfuse/vehicle/dead_reckoning.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "mapfuse/core/error.hpp"

namespace mapfuse::vehicle {
namespace {

double wheelSpeedAt(const std::vector<WheelSample>& wheel, double t) {
  if (t <= wheel.front().stamp) return wheel.front().speed;
  if (t >= wheel.back().stamp) return wheel.back().speed;
  auto it = std::upper_bound(wheel.begin(), wheel.end(), t,
                             [](double v, const WheelSample& w) { return v < w.stamp; });
  const WheelSample& b = *it;
  const WheelSample& a = *(it - 1);
  const double dt = b.stamp - a.stamp;
  const double alpha = dt > 0.0 ? (t - a.stamp) / dt : 0.0;
  return a.speed + alpha * (b.speed - a.speed);
}

}  // namespace

std::vector<Pose3> deadReckon(const std::vector<ImuSample>& imu,
                              const std::vector<WheelSample>& wheel,
                              const std::vector<double>& stamps, const DeadReckoningSettings& s) {
  if (imu.size() < 2) throw InputError("dead reckoning: fewer than 2 IMU samples");
  if (wheel.empty()) throw InputError("dead reckoning: no wheel samples");
  for (std::size_t i = 1; i < imu.size(); ++i)
    if (imu[i].stamp < imu[i - 1].stamp)
      throw InputError("dead reckoning: IMU stamps go backwards at sample " + std::to_string(i));
  for (std::size_t i = 1; i < wheel.size(); ++i)
    if (wheel[i].stamp < wheel[i - 1].stamp)
      throw InputError("dead reckoning: wheel stamps go backwards at sample " + std::to_string(i));

  // Integrate on the IMU grid (midpoint rule for rotation, trapezoid for speed).
  std::vector<Pose3> trajectory(imu.size(), Pose3::Identity());
  Pose3 T = Pose3::Identity();
  for (std::size_t i = 1; i < imu.size(); ++i) {
    const double dt = imu[i].stamp - imu[i - 1].stamp;
    const Eigen::Vector3d w = 0.5 * (imu[i].gyro + imu[i - 1].gyro) - s.gyro_bias;
    const double v = 0.5 * s.wheel_scale *
                     (wheelSpeedAt(wheel, imu[i - 1].stamp) + wheelSpeedAt(wheel, imu[i].stamp));
    const Eigen::Matrix3d dR =
        Eigen::AngleAxisd(w.norm() * dt, w.norm() > 0 ? w.normalized() : Eigen::Vector3d::UnitZ())
            .toRotationMatrix();
    const Eigen::Matrix3d R_half =
        T.linear() * Eigen::AngleAxisd(0.5 * w.norm() * dt,
                                       w.norm() > 0 ? w.normalized() : Eigen::Vector3d::UnitZ())
                         .toRotationMatrix();
    T.translation() += R_half * Eigen::Vector3d(v * dt, 0.0, 0.0);
    T.linear() = T.linear() * dR;
    trajectory[i] = T;
  }
  std::vector<Pose3> out;
  out.reserve(stamps.size());
  for (double t : stamps) {
    if (t <= imu.front().stamp) {
      out.push_back(trajectory.front());
      continue;
    }
    if (t >= imu.back().stamp) {
      out.push_back(trajectory.back());
      continue;
    }
    auto it = std::upper_bound(imu.begin(), imu.end(), t,
                               [](double v, const ImuSample& m) { return v < m.stamp; });
    const std::size_t j = std::size_t(it - imu.begin());
    const double dt = imu[j].stamp - imu[j - 1].stamp;
    const double alpha = dt > 0.0 ? (t - imu[j - 1].stamp) / dt : 0.0;
    out.push_back(interpolate(trajectory[j - 1], trajectory[j], alpha));
  }
  return out;
}

std::vector<std::size_t> selectKeyframes(const std::vector<Pose3>& poses, double spacing,
                                         double max_angle) {
  std::vector<std::size_t> out;
  if (poses.empty()) return out;
  out.push_back(0);
  double path = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    path += (poses[i].translation() - poses[i - 1].translation()).norm();
    const Pose3& last = poses[out.back()];
    const double angle = Eigen::AngleAxisd(last.linear().transpose() * poses[i].linear()).angle();
    if (path >= spacing || angle >= max_angle) {
      out.push_back(i);
      path = 0.0;
    }
  }
  if (out.back() != poses.size() - 1) out.push_back(poses.size() - 1);
  return out;
}

}  // namespace mapfuse::vehicle
