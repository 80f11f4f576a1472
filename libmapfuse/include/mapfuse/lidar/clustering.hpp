#pragma once
/// @file Euclidean clustering (connected components of the "closer than a tolerance" graph)
/// on a hashed grid whose cell edge equals the tolerance, so every neighbour lies in the 27
/// cells around a point. Used per label by the error minimisation (Jeong et al. 2018, §2.1.2).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mapfuse/core/param.hpp"

namespace mapfuse::lidar {

struct ClusteringSettings {
  double tolerance = 0.5;  ///< m, maximum gap between two points of one cluster
  int min_points = 5;      ///< smaller components are reported with cluster id -1

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("cluster_tolerance", tolerance, "m", "Euclidean clustering gap", gt(0) & le(100));
    v("cluster_min_points", min_points, "", "smallest cluster judged by a forest", in(1, 1e9));
  }
};

/// @brief Cluster id per point (0..n-1 in order of first point, -1 for components below
/// min_points). Deterministic.
/// @param points the points to cluster (any frame)
/// @param[out] num_clusters number of clusters with id >= 0
std::vector<int> euclideanClusters(const std::vector<Eigen::Vector3f>& points,
                                   const ClusteringSettings& s, int* num_clusters);

}  // namespace mapfuse::lidar
