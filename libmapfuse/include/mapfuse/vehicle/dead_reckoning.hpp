#pragma once
/// @file Ego-motion from IMU gyro + wheel odometry (Song et al. 2023 §3.1): the attitude is
/// integrated from bias-corrected angular rates, the position from the scaled wheel speed
/// along the body x axis. Keyframes are chosen at a configurable travelled distance.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"

namespace mapfuse::vehicle {

/// Corrections of the dead reckoning (docs/lsm-build.md); each declared once, in visit().
struct DeadReckoningSettings {
  double wheel_scale = 1.0;                             ///< multiplies the wheel speed
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();  ///< rad/s, subtracted from the gyro

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("wheel_scale", wheel_scale, "", "dead reckoning: wheel speed scale", gt(0) & le(10));
    v("gyro_bias_x", gyro_bias.x(), "rad/s", "dead reckoning: gyro bias x", in(-1, 1));
    v("gyro_bias_y", gyro_bias.y(), "rad/s", "dead reckoning: gyro bias y", in(-1, 1));
    v("gyro_bias_z", gyro_bias.z(), "rad/s", "dead reckoning: gyro bias z", in(-1, 1));
  }
};

/// Keyframe selection along the ego-motion (selectKeyframes).
struct KeyframeSettings {
  double spacing = 10.0;   ///< m of travelled path between keyframes
  double max_angle = 0.3;  ///< rad of rotation that forces a keyframe

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("keyframe_spacing", spacing, "m", "travelled distance between keyframes", gt(0) & le(10000));
    v("keyframe_max_angle", max_angle, "rad", "rotation that forces a keyframe", gt(0) & le(10));
  }
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
