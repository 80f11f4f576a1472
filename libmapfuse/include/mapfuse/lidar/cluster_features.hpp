#pragma once
/// @file Geometric features of a cluster (Jeong et al. 2018, eq. 4): X/Y/Z extents and the
/// eigenvalue features of the 3D covariance, with e1 >= e2 >= e3 the eigenvalues normalised by
/// their sum: linearity (e1-e2)/e1, planarity (e2-e3)/e1, scattering e3/e1, omnivariance
/// (e1 e2 e3)^(1/3), anisotropy (e1-e3)/e1, eigenentropy -sum e_i ln e_i.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace mapfuse::lidar {

constexpr int kNumClusterFeatures = 9;
using ClusterFeatures = std::array<float, kNumClusterFeatures>;

/// Feature names in vector order.
extern const char* const kClusterFeatureNames[kNumClusterFeatures];

/// @brief eq. (4) features of the points `members` of `points`.
/// Degenerate clusters (fewer than 3 points, or zero spread) give zero eigen features.
ClusterFeatures clusterFeatures(const std::vector<Eigen::Vector3f>& points,
                                const std::vector<int>& members);

}  // namespace mapfuse::lidar
