#pragma once
/// @file Scan-to-local-map registration of the LiDAR odometry: ICP with the Geman-McClure kernel
/// and correspondences within a distance threshold (kiss-icp, Vizzo et al. 2023, eq. (9)-(12)),
/// point-to-plane where the matched map voxel is planar, point-to-point elsewhere. Gauss-Newton
/// on SE(3) with left perturbation T <- exp(dx) T, dx = (rho, phi).
#include <vector>

#include <Eigen/Core>

#include "mapfuse/core/se3.hpp"
#include "mapfuse/lidar/local_voxel_map.hpp"

namespace mapfuse::lidar {

struct MapRegistrationSettings {
  int max_iterations = 100;   ///< Gauss-Newton iterations
  double convergence = 1e-4;  ///< |dx| (m and rad together) below which it has converged
  /// m: when max_iterations run out with the correspondences switching back and forth, it has
  /// converged if the last 10 poses all lie this close to the final one (and a tenth of it, rad)
  double oscillation_tolerance = 0.01;
  int min_correspondences = 30;  ///< fewer: stop, not converged
  bool point_to_plane = true;    ///< false: point-to-point everywhere (kiss-icp as published)
};

struct MapRegistrationResult {
  Pose3 T_map_scan = Pose3::Identity();
  bool converged = false;
  int iterations = 0;
  int correspondences = 0;    ///< source points within max_distance of the map at the final pose
  double inlier_share = 0.0;  ///< correspondences / source points
  double rmse = 0.0;          ///< m, of the correspondences at the final pose
};

/// @brief Registers `source` (scan frame) to `map` from `T_init`.
/// @param max_distance correspondence threshold, m (<= the map's voxel size for exact search)
/// @param kernel_scale Geman-McClure scale, m: weight = k^2 / (k + r^2)^2 with r^2 in m^2
MapRegistrationResult registerToMap(const LocalVoxelMap& map,
                                    const std::vector<Eigen::Vector3d>& source, const Pose3& T_init,
                                    double max_distance, double kernel_scale,
                                    const MapRegistrationSettings& settings);

}  // namespace mapfuse::lidar
