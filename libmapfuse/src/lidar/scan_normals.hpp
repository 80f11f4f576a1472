#pragma once
/// @file Surface normals of a scan's points for point-to-plane registration: PCA of the k nearest
/// neighbours (fusion/voxel_hash.hpp, 27-cell search), the eigenvector of the smallest spread.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/fusion/voxel_hash.hpp"

namespace mapfuse::lidar {

/// Normals of one scan computed on demand (the local map asks only for the points it keeps).
class ScanNormals {
 public:
  /// @param points the scan (kept by reference: it must outlive this object)
  /// @param k neighbours (>= 3); @param cell search cell edge, m (> 0)
  /// @throws InputError for k < 3 or cell <= 0.
  ScanNormals(const std::vector<Eigen::Vector3d>& points, int k, double cell);
  /// @brief Unit normal of point i, or zero (see estimateNormals).
  Eigen::Vector3d at(std::size_t i) const;

 private:
  const std::vector<Eigen::Vector3d>& points_;
  fusion::VoxelIndex index_;
  int k_;
};

/// @brief One unit normal per point, or zero where fewer than 3 neighbours lie within the search
/// cells or they lie on a line (middle spread below 1 % of the largest: one scan ring).
/// @param k neighbours (3..32); @param cell search cell edge, m (> 0): neighbours are exact within
/// this radius
/// @throws InputError for k < 3 or cell <= 0.
std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points, int k,
                                             double cell);

}  // namespace mapfuse::lidar
