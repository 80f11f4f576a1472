#pragma once
/// @file Drives through the simulator world (docs/simulate.md "Drives and sensor errors"):
/// routes as random walks on the lane graph, the true body trajectory (speed, lateral offset,
/// pitch / roll oscillation), and the vehicle's sensors with per-traversal errors: IMU (gyro
/// bias + white noise), wheel odometry (scale error + noise), GPS at 1 Hz (bias of 1-3 m that
/// random-walks, white noise, multipath outliers), and the drifting dead-reckoned odometry.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <functional>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

struct DriveParams {
  double speed_min = 8.0;                 ///< m/s, per-traversal speed drawn in [min, max]
  double speed_max = 14.0;                ///< m/s
  double lateral_offset_sigma = 0.2;      ///< m, per-traversal offset from the lane centre
  double imu_rate = 100.0;                ///< Hz
  double wheel_rate = 50.0;               ///< Hz
  double gps_rate = 1.0;                  ///< Hz
  double camera_rate = 10.0;              ///< Hz
  double gps_bias_min = 1.0;              ///< m, magnitude of the initial horizontal bias
  double gps_bias_max = 3.0;              ///< m
  double gps_bias_walk = 0.05;            ///< m/sqrt(s), random walk of the bias per axis
  double gps_white_sigma = 0.5;           ///< m, horizontal white noise per axis
  double gps_vertical_sigma = 2.0;        ///< m, vertical white noise
  double gps_outlier_probability = 0.02;  ///< per fix
  double gps_outlier_min = 5.0;           ///< m, multipath outlier magnitude range
  double gps_outlier_max = 20.0;          ///< m
  double gps_reported_sigma_h = 2.5;      ///< m, sigma the receiver reports
  double gps_reported_sigma_v = 4.0;      ///< m
  double wheel_scale_sigma = 0.01;        ///< per-traversal wheel scale error, 1-sigma
  double imu_pitch_mount = 0.0;     ///< rad, IMU mounted pitched against the body (injected bias)
  double wheel_scale_offset = 0.0;  ///< added to the drawn wheel scale error (injected bias)
  double wheel_speed_noise = 0.05;  ///< m/s, white noise per wheel sample
  double gyro_bias_sigma = 0.0005;  ///< rad/s, per-traversal bias per axis
  double gyro_noise_density = 0.0005;  ///< rad/s/sqrt(Hz)
  double accel_noise = 0.05;           ///< m/s^2 per sample
  double attitude_noise = 0.001;       ///< rad, levelled roll/pitch noise of the odometry
  double pitch_amplitude = 0.01;       ///< rad, body pitch oscillation
  double pitch_frequency = 0.7;        ///< Hz
  double roll_amplitude = 0.005;       ///< rad, body roll oscillation
  double roll_frequency = 0.5;         ///< Hz

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("speed_min", speed_min, "m/s", "per-traversal speed, lower bound", gt(0.5) & le(100));
    v("speed_max", speed_max, "m/s", "per-traversal speed, upper bound", gt(0.5) & le(100));
    v.relation("speed_max", speed_max, speed_max >= speed_min, ">= speed_min");
    v("lateral_offset_sigma", lateral_offset_sigma, "m",
      "per-traversal offset from the lane centre", in(0, 10));
    // a drive holds one sample per IMU period (the simulation step)
    v("imu_rate", imu_rate, "Hz", "IMU rate (simulation step)", in(1, 10000));
    v("wheel_rate", wheel_rate, "Hz", "wheel odometry rate", gt(0) & le(10000));
    v.relation("wheel_rate", wheel_rate, dividesImuRate(wheel_rate), "divides imu_rate");
    v("gps_rate", gps_rate, "Hz", "GPS fix rate", gt(0) & le(10000));
    v.relation("gps_rate", gps_rate, dividesImuRate(gps_rate), "divides imu_rate");
    v("camera_rate", camera_rate, "Hz", "camera frame rate", gt(0) & le(10000));
    v.relation("camera_rate", camera_rate, dividesImuRate(camera_rate), "divides imu_rate");
    v("gps_bias_min", gps_bias_min, "m", "initial horizontal GPS bias magnitude, min", in(0, 1000));
    v("gps_bias_max", gps_bias_max, "m", "initial horizontal GPS bias magnitude, max", in(0, 1000));
    v.relation("gps_bias_max", gps_bias_max, gps_bias_max >= gps_bias_min, ">= gps_bias_min");
    v("gps_bias_walk", gps_bias_walk, "m/sqrt(s)", "random walk of the GPS bias per axis",
      in(0, 100));
    v("gps_white_sigma", gps_white_sigma, "m", "GPS horizontal white noise per axis", in(0, 1000));
    v("gps_vertical_sigma", gps_vertical_sigma, "m", "GPS vertical white noise", in(0, 1000));
    v("gps_outlier_probability", gps_outlier_probability, "",
      "multipath outlier probability per fix", in(0, 1));
    v("gps_outlier_min", gps_outlier_min, "m", "multipath outlier magnitude, min", in(0, 10000));
    v("gps_outlier_max", gps_outlier_max, "m", "multipath outlier magnitude, max", in(0, 10000));
    v.relation("gps_outlier_max", gps_outlier_max, gps_outlier_max >= gps_outlier_min,
               ">= gps_outlier_min");
    v("gps_reported_sigma_h", gps_reported_sigma_h, "m", "horizontal sigma reported in fixes",
      gt(0) & le(1000));
    v("gps_reported_sigma_v", gps_reported_sigma_v, "m", "vertical sigma reported in fixes",
      gt(0) & le(1000));
    v("wheel_scale_sigma", wheel_scale_sigma, "", "per-traversal wheel scale error, 1-sigma",
      in(0, 1));
    v("imu_pitch_mount", imu_pitch_mount, "rad",
      "IMU pitched against the body: gyro and accel read in the tilted frame", in(-0.5, 0.5));
    v("wheel_scale_offset", wheel_scale_offset, "", "added to every drive's wheel scale error",
      in(-0.5, 0.5));
    v("wheel_speed_noise", wheel_speed_noise, "m/s", "wheel speed white noise", in(0, 100));
    v("gyro_bias_sigma", gyro_bias_sigma, "rad/s", "per-traversal gyro bias per axis", in(0, 1));
    v("gyro_noise_density", gyro_noise_density, "rad/s/sqrt(Hz)", "gyro white noise density",
      in(0, 1));
    v("accel_noise", accel_noise, "m/s^2", "accelerometer white noise per sample", in(0, 100));
    v("attitude_noise", attitude_noise, "rad", "levelled roll/pitch noise of the odometry",
      in(0, 1));
    v("pitch_amplitude", pitch_amplitude, "rad", "body pitch oscillation amplitude", in(0, 1));
    v("pitch_frequency", pitch_frequency, "Hz", "body pitch oscillation frequency", in(0, 100));
    v("roll_amplitude", roll_amplitude, "rad", "body roll oscillation amplitude", in(0, 1));
    v("roll_frequency", roll_frequency, "Hz", "body roll oscillation frequency", in(0, 100));
  }

  /// @brief True when `rate` is at most imu_rate and imu_rate is an integer multiple of it.
  bool dividesImuRate(double rate) const;
};

/// @brief IMU-rate samples between two camera frames (frame f is sample f * stride).
std::size_t cameraStride(const DriveParams& DP);

/// One GPS fix with its true error (for statistics).
struct GpsRecord {
  GpsFix fix;
  Eigen::Vector3d error_enu = Eigen::Vector3d::Zero();  ///< fix - truth, m
  bool outlier = false;
};

struct ImuRecord {
  double stamp = 0.0;
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   ///< rad/s body
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< m/s^2 specific force, body
};

struct WheelRecord {
  double stamp = 0.0;
  double speed = 0.0;  ///< m/s
};

/// One simulated traversal, sampled at the IMU rate.
struct Drive {
  std::string drive_id, vehicle_id;
  double speed = 0.0;  ///< m/s, true
  double wheel_scale_error = 0.0;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector2d gps_bias0 = Eigen::Vector2d::Zero();
  std::vector<double> stamps;    ///< s, IMU rate
  std::vector<Pose3> truth;      ///< T_enu_body
  std::vector<Pose3> odom;       ///< T_odom_body, dead reckoned
  std::vector<double> distance;  ///< true travelled distance, m
  std::vector<ImuRecord> imu;
  std::vector<WheelRecord> wheel;
  std::vector<GpsRecord> gps;

  double length() const { return distance.empty() ? 0.0 : distance.back(); }
};

/// @brief Random walks on the lane graph: `count` routes of about `length` m (shorter at dead
/// ends), each the concatenated centreline of its lanes, cut 1 km past `length` at the most.
/// `outward`: at each lane end the route takes, of the lanes not yet driven, the one whose end
/// lies farthest from the route's start, so it never returns (a drive with nothing to loop on).
std::vector<Polyline> planRoutes(const World& world, int count, double length, uint64_t seed,
                                 bool outward = false);

/// @brief Simulates one traversal of `route`. @param seed this traversal's own seed.
/// @param surface the road surface's height at an ENU point (World::surface_height): the body
/// rolls with the road's cross-slope under it; empty: level across.
Drive simulateDrive(const Polyline& route, const DriveParams& params, const geo::EnuConverter& enu,
                    uint64_t seed,
                    const std::function<double(const Eigen::Vector3d&)>& surface = {});

/// @brief Seed of item `index` derived from a base seed (splitmix64), so traversals are
/// independent of the order they are simulated in.
uint64_t deriveSeed(uint64_t base, uint64_t index);

}  // namespace mapfuse::sim
