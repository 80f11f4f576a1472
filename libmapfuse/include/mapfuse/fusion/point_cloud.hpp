#pragma once
/// @file Point clouds for registration: points with optional per-point covariances and labels,
/// voxel downsampling and GICP covariance estimation (Segal et al. 2009, plane regularisation).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::fusion {

/// A point cloud. `covariances` and `labels` are either empty or one per point.
struct Cloud {
  std::vector<Eigen::Vector3d> points;       ///< m
  std::vector<Eigen::Matrix3d> covariances;  ///< m^2, same frame as points (empty = none yet)
  std::vector<uint8_t> labels;               ///< semantic class per point (empty = unlabelled)

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
};

/// @brief Centroid per voxel (integer-keyed grid, deterministic output order by voxel key).
/// Covariances, when present, are averaged; the label is the majority label of the voxel
/// (ties go to the smaller label).
/// @param in cloud to reduce
/// @param voxel_size voxel edge length, m (> 0)
/// @throws InputError when voxel_size <= 0 or sizes of the optional fields mismatch.
Cloud voxelDownsample(const Cloud& in, double voxel_size);

/// @brief GICP covariances from the k nearest neighbours of each point, plane-regularised:
/// eigenvalues replaced by (eps, 1, 1) * scale as in Segal et al. 2009, so a point is a
/// small disc along its local surface. Neighbours are searched in the 27 cells of a voxel hash
/// of edge `neighbor_cell_size`; a point with fewer than 3 neighbours there gets an isotropic
/// covariance (it then acts as a point-to-point correspondence).
/// @param cloud cloud whose covariances are (re)computed in place
/// @param num_neighbors k (>= 3)
/// @param neighbor_cell_size voxel edge of the neighbour search, m (> 0); about 3-4x the point
/// spacing (1.0 m suits 0.25 m-voxelised LiDAR scans)
/// @throws InputError when num_neighbors < 3 or neighbor_cell_size <= 0.
void estimateCovariances(Cloud& cloud, int num_neighbors = 10, double neighbor_cell_size = 1.0);

/// @brief Plane regularisation of one sample covariance: eigenvalues -> (eps, 1, 1).
Eigen::Matrix3d planeRegularized(const Eigen::Matrix3d& sample_cov, double eps = 1e-3);

/// @brief Applies T to points and rotates covariances (labels kept).
Cloud transformCloud(const Cloud& in, const Pose3& T);

/// @brief Appends b to a (both must have the same optional fields, or a empty).
void appendCloud(Cloud& a, const Cloud& b);

}  // namespace mapfuse::fusion
