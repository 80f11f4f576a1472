#pragma once
/// @file Ego-motion from IMU gyro + accelerometer + wheel odometry (Song et al. 2023 §3.1): the
/// attitude is integrated from bias-corrected angular rates and held to gravity by the
/// accelerometer (a complementary filter, Mahony et al. 2008: the specific force minus the
/// motion the wheel speed and gyro explain is gravity; its direction corrects roll and pitch and
/// a slow integral estimates the gyro's roll/pitch bias), the position from the scaled wheel
/// speed along the body x axis, so the height follows the road's grade. Without the gravity
/// correction the pitch is integrated gyro alone: a 0.0005 rad/s bias tilts it by 0.075 rad
/// after 150 s, and the height drifts by 2-3 % of the distance (issue 33). Keyframes are chosen
/// at a configurable travelled distance.
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
  double gravity_gain = 0.5;        ///< 1/s, proportional gain of the gravity correction (0: off)
  double gravity_bias_gain = 0.05;  ///< 1/s^2, integral gain (gyro roll/pitch bias estimate)
  double gravity_tolerance = 0.1;   ///< share of g the gravity estimate may deviate and be used
  double accel_slope_window = 0.5;  ///< s each side for the wheel speed's time derivative

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("wheel_scale", wheel_scale, "", "dead reckoning: wheel speed scale", gt(0) & le(10));
    v("gyro_bias_x", gyro_bias.x(), "rad/s", "dead reckoning: gyro bias x", in(-1, 1));
    v("gyro_bias_y", gyro_bias.y(), "rad/s", "dead reckoning: gyro bias y", in(-1, 1));
    v("gyro_bias_z", gyro_bias.z(), "rad/s", "dead reckoning: gyro bias z", in(-1, 1));
    // time constant 1/gain: the pitch error left by a gyro bias b is b / gain before the
    // integral has learnt b; critical damping at bias_gain = gain^2 / 4
    v("gravity_gain", gravity_gain, "1/s", "dead reckoning: gravity correction gain (0: off)",
      in(0, 100));
    v("gravity_bias_gain", gravity_bias_gain, "1/s^2",
      "dead reckoning: gravity correction integral gain (gyro bias)", in(0, 100));
    v("gravity_tolerance", gravity_tolerance, "",
      "dead reckoning: use the gravity estimate when its norm is within this share of g",
      gt(0) & le(1));
    v("accel_slope_window", accel_slope_window, "s",
      "dead reckoning: half window of the wheel speed derivative", gt(0) & le(100));
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
/// (odom: origin at the body at the first IMU sample, z up along gravity, x the body's heading
/// there; the body frame itself when the accelerometer gives no gravity, e.g. all zeros).
/// Stamps outside the IMU span are clamped.
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
