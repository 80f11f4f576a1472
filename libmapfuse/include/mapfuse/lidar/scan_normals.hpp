#pragma once
/// @file Surface normals of a scan's points for point-to-plane registration: PCA of the k nearest
/// neighbours (fusion/voxel_hash.hpp, 27-cell search), the eigenvector of the smallest spread.
#include <Eigen/Core>
#include <vector>

namespace mapfuse::lidar {

/// @brief One unit normal per point, or zero where fewer than 3 neighbours lie within the search
/// cells or they lie on a line (middle spread below 1 % of the largest: one scan ring).
/// @param k neighbours (>= 3); @param cell search cell edge, m (> 0): neighbours are exact within
/// this radius
/// @throws InputError for k < 3 or cell <= 0.
std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points, int k,
                                             double cell);

}  // namespace mapfuse::lidar
