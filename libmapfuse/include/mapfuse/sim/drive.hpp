#pragma once
/// @file Drives through the simulator world (docs/simulate.md "Drives and sensor errors"):
/// routes as random walks on the lane graph, the true body trajectory (speed, lateral offset,
/// pitch / roll oscillation), and the vehicle's sensors with per-traversal errors: IMU (gyro
/// bias + white noise), wheel odometry (scale error + noise), GPS at 1 Hz (bias of 1-3 m that
/// random-walks, white noise, multipath outliers), and the drifting dead-reckoned odometry.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mapfuse/core/lsm.hpp"
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
  double wheel_speed_noise = 0.05;        ///< m/s, white noise per wheel sample
  double gyro_bias_sigma = 0.0005;        ///< rad/s, per-traversal bias per axis
  double gyro_noise_density = 0.0005;     ///< rad/s/sqrt(Hz)
  double accel_noise = 0.05;              ///< m/s^2 per sample
  double attitude_noise = 0.001;          ///< rad, levelled roll/pitch noise of the odometry
  double pitch_amplitude = 0.01;          ///< rad, body pitch oscillation
  double pitch_frequency = 0.7;           ///< Hz
  double roll_amplitude = 0.005;          ///< rad, body roll oscillation
  double roll_frequency = 0.5;            ///< Hz
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
/// ends), each the concatenated centreline of its lanes.
std::vector<Polyline> planRoutes(const World& world, int count, double length, uint64_t seed);

/// @brief Simulates one traversal of `route`. @param seed this traversal's own seed.
Drive simulateDrive(const Polyline& route, const DriveParams& params, const geo::EnuConverter& enu,
                    uint64_t seed);

/// @brief Seed of item `index` derived from a base seed (splitmix64), so traversals are
/// independent of the order they are simulated in.
uint64_t deriveSeed(uint64_t base, uint64_t index);

}  // namespace mapfuse::sim
