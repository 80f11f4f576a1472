#pragma once
/// @file The ego drive of the LiDAR simulator: the vehicle follows the right lane's centre at
/// constant speed; the IMU pose is T_world_imu (x forward, y left, z up) and the Velodyne pose
/// T_world_velo = T_world_imu * T_imu_velo with the KITTI extrinsics.
#include "mapfuse/core/se3.hpp"
#include "mapfuse/sim/lidar_road.hpp"

namespace mapfuse::sim {

struct EgoDrive {
  double start = 25.0;        ///< m, arc length at t = 0
  double speed = 8.0;         ///< m/s
  double lateral = -1.75;     ///< m, lane centre (right lane: negative)
  double velo_height = 1.73;  ///< m, Velodyne above the road
};

/// @brief T_world_imu at time t (s) such that the Velodyne sits velo_height above the road.
Pose3 egoImuPose(const Road& road, const EgoDrive& drive, const Pose3& T_imu_velo, double t);

}  // namespace mapfuse::sim
