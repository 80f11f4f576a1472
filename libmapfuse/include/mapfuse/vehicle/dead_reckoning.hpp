#pragma once
/// @file Ego-motion from IMU gyro + wheel odometry (Song et al. 2023 §3.1): the attitude is
/// integrated from bias-corrected angular rates, the position from the scaled wheel speed
/// along the body x axis. Keyframes are chosen at a configurable travelled distance.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::vehicle {

struct ImuSample {
  double stamp = 0.0;                               ///< s
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   ///< rad/s, body frame
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< m/s^2, body frame (unused here)
};

struct WheelSample {
  double stamp = 0.0;  ///< s
  double speed = 0.0;  ///< m/s, forward
};

struct DeadReckoningSettings {
  double wheel_scale = 1.0;                             ///< multiplies the wheel speed
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();  ///< rad/s, subtracted from the gyro
};

/// @brief Integrates IMU + wheel streams and returns T_odom_body at each requested stamp
/// (odom = body pose at the first IMU sample). Stamps outside the IMU span are clamped.
/// @throws InputError when the IMU or wheel stream is empty or not sorted.
std::vector<Pose3> deadReckon(const std::vector<ImuSample>& imu,
                              const std::vector<WheelSample>& wheel,
                              const std::vector<double>& stamps,
                              const DeadReckoningSettings& settings);

/// @brief Indices of keyframes: the first frame, then every frame at least `spacing` metres
/// (path length) or `max_angle` rad of rotation after the previous keyframe, and the last.
std::vector<std::size_t> selectKeyframes(const std::vector<Pose3>& poses, double spacing,
                                         double max_angle);

}  // namespace mapfuse::vehicle
