#pragma once
/// @file An independent reference for the LiDAR odometry on real drives without truth: pairwise
/// GICP (fusion/gicp.hpp, Segal et al. 2009) between scans a few frames apart, on static
/// structure only: ground and every object the size of a road user removed by the truth-free rule
/// of lidar/scan_geometry.hpp, so that moving traffic cannot pull the result along. It shares
/// nothing with the odometry but that rule: no local map, no prediction, no de-skew, another
/// registration (plane-to-plane at 0.1 m instead of point-to-point at 0.5-1.5 m).
#include <Eigen/Core>
#include <vector>

#include "mapfuse/core/se3.hpp"
#include "mapfuse/lidar/scan_geometry.hpp"

namespace mapfuse::lidar {

struct StaticRegistrationSettings {
  double voxel_size = 0.1;  ///< m, downsampling of the static points
  double min_range = 3.0;   ///< m
  double max_range = 60.0;  ///< m
  double min_height = 0.0;  ///< m above ground; static points lower than this are left out too
  SceneGeometrySettings geometry;
};

/// @brief T_a_b of scan b in scan a (Velodyne frames), from static structure only.
/// @param init starting guess (identity when unknown)
/// @param fitness receives the share of b's static points matched at the end (optional)
Pose3 registerStaticStructure(const std::vector<Eigen::Vector3f>& scan_a,
                              const std::vector<Eigen::Vector3f>& scan_b, const Pose3& init,
                              const StaticRegistrationSettings& settings,
                              double* fitness = nullptr);

}  // namespace mapfuse::lidar
