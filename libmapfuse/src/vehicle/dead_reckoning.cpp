#include "mapfuse/vehicle/dead_reckoning.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/pose_at_stamp.hpp"

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

constexpr double kGravity = 9.80665;  // m/s^2

/// Rate of change of the wheel speed at t: central difference over ±window (clamped).
double wheelSlopeAt(const std::vector<WheelSample>& wheel, double t, double window) {
  const double t0 = std::max(wheel.front().stamp, t - window);
  const double t1 = std::min(wheel.back().stamp, t + window);
  return t1 > t0 ? (wheelSpeedAt(wheel, t1) - wheelSpeedAt(wheel, t0)) / (t1 - t0) : 0.0;
}

/// Unit up axis (body frame) from the specific force: f minus the body's own acceleration along
/// its path, (dv/dt, v w_z, -v w_y) (R (v e_x) differentiated), is gravity. Empty (zero) when
/// its norm is not within `tolerance` of g (a stream without accelerometer, a jolt).
Eigen::Vector3d upFromAccel(const Eigen::Vector3d& f, double v, double v_dot,
                            const Eigen::Vector3d& w, double tolerance) {
  const Eigen::Vector3d g = f - Eigen::Vector3d(v_dot, v * w.z(), -v * w.y());
  if (std::abs(g.norm() - kGravity) > tolerance * kGravity) return Eigen::Vector3d::Zero();
  return g.normalized();
}

/// Roll and pitch (yaw 0) of a body whose up axis is `up` (body frame): up = R^T e_z =
/// (-sin p, sin r cos p, cos r cos p) for R = Rz(0) Ry(p) Rx(r).
Eigen::Matrix3d levelledAttitude(const Eigen::Vector3d& up) {
  const double pitch = std::atan2(-up.x(), std::hypot(up.y(), up.z()));
  const double roll = std::atan2(up.y(), up.z());
  return (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// Initial attitude: levelled by the mean up axis of the first `window` s (identity without one).
Eigen::Matrix3d initialAttitude(const std::vector<ImuSample>& imu,
                                const std::vector<WheelSample>& wheel,
                                const DeadReckoningSettings& s) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0;
       i < imu.size() && imu[i].stamp <= imu.front().stamp + s.accel_slope_window; ++i) {
    const double t = imu[i].stamp;
    sum += upFromAccel(imu[i].accel, s.wheel_scale * wheelSpeedAt(wheel, t),
                       s.wheel_scale * wheelSlopeAt(wheel, t, s.accel_slope_window),
                       imu[i].gyro - s.gyro_bias, s.gravity_tolerance);
  }
  if (s.gravity_gain <= 0.0 || sum.norm() < 1e-9) return Eigen::Matrix3d::Identity();
  return levelledAttitude(sum.normalized());
}

/// Rotation over dt by the angular rate w (rad/s, body frame).
Eigen::Matrix3d rotationOver(const Eigen::Vector3d& w, double dt) {
  const double a = w.norm() * dt;
  return Eigen::AngleAxisd(a, a > 0 ? w.normalized() : Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

/// The IMU + wheel integration on the IMU grid (midpoint rule for rotation, trapezoid for speed),
/// the attitude held to gravity by the complementary filter (file comment).
std::vector<Pose3> integrate(const std::vector<ImuSample>& imu,
                             const std::vector<WheelSample>& wheel,
                             const DeadReckoningSettings& s) {
  std::vector<Pose3> trajectory(imu.size(), Pose3::Identity());
  Pose3 T = Pose3::Identity();
  T.linear() = initialAttitude(imu, wheel, s);
  trajectory[0] = T;
  Eigen::Vector3d bias_estimate = Eigen::Vector3d::Zero();  // on top of s.gyro_bias
  for (std::size_t i = 1; i < imu.size(); ++i) {
    const double dt = imu[i].stamp - imu[i - 1].stamp;
    const double tm = 0.5 * (imu[i].stamp + imu[i - 1].stamp);
    Eigen::Vector3d w = 0.5 * (imu[i].gyro + imu[i - 1].gyro) - s.gyro_bias - bias_estimate;
    const double v = 0.5 * s.wheel_scale *
                     (wheelSpeedAt(wheel, imu[i - 1].stamp) + wheelSpeedAt(wheel, imu[i].stamp));
    if (s.gravity_gain > 0.0) {
      const Eigen::Vector3d up_meas = upFromAccel(
          0.5 * (imu[i].accel + imu[i - 1].accel), v,
          s.wheel_scale * wheelSlopeAt(wheel, tm, s.accel_slope_window), w, s.gravity_tolerance);
      if (up_meas.squaredNorm() > 0.0) {
        const Eigen::Vector3d e = up_meas.cross(T.linear().transpose() * Eigen::Vector3d::UnitZ());
        w += s.gravity_gain * e;
        bias_estimate -= s.gravity_bias_gain * e * dt;
      }
    }
    T.translation() += T.linear() * rotationOver(w, 0.5 * dt) * Eigen::Vector3d(v * dt, 0.0, 0.0);
    T.linear() = T.linear() * rotationOver(w, dt);
    trajectory[i] = T;
  }
  return trajectory;
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
  const std::vector<Pose3> trajectory = integrate(imu, wheel, s);
  std::vector<Pose3> out;
  out.reserve(stamps.size());
  for (double t : stamps) {
    const auto T = poseAtStamp(
        imu.size(), t, [&](std::size_t i) { return imu[i].stamp; },
        [&](std::size_t i) { return trajectory[i]; });
    // frames outside the IMU's time span take its first or last pose
    out.push_back(T ? *T : (t <= imu.front().stamp ? trajectory.front() : trajectory.back()));
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
