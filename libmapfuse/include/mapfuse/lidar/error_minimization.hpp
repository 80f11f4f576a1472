#pragma once
/// @file Per-frame error minimisation (Jeong et al. 2018, §2.1.2): the labelled points of a
/// frame are clustered per label, each cluster described by its eq. (4) features, and the
/// label's random forest drops clusters it judges wrongly labelled before fusion.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mapfuse/lidar/cluster_classifier.hpp"
#include "mapfuse/lidar/clustering.hpp"

namespace mapfuse::lidar {

/// One cluster of same-label points.
struct LabeledCluster {
  uint8_t label = 0;         ///< LidarClass
  std::vector<int> members;  ///< indices into the point array
  ClusterFeatures features{};
};

/// @brief Clusters the points of each label separately (only labels with `mask[label]`).
/// @param points labelled points (e.g. the projected points of one scan, velo frame)
/// @param labels LidarClass per point
std::vector<LabeledCluster> labelClusters(const std::vector<Eigen::Vector3f>& points,
                                          const std::vector<uint8_t>& labels,
                                          const ClusteringSettings& settings,
                                          const std::array<bool, kNumLidarClasses>& mask);

struct ErrorMinimizationStats {
  std::size_t clusters = 0;           ///< clusters examined
  std::size_t rejected_clusters = 0;  ///< clusters the forests dropped
  std::size_t rejected_points = 0;    ///< points in dropped clusters
};

/// @brief Keep mask per point: 0 for points in clusters the classifier rejects. Labels without
/// a forest are not clustered (all kept); points in components below min_points are kept.
std::vector<uint8_t> minimizeErrors(const std::vector<Eigen::Vector3f>& points,
                                    const std::vector<uint8_t>& labels,
                                    const ClusterClassifier& classifier,
                                    const ClusteringSettings& settings,
                                    ErrorMinimizationStats* stats);

}  // namespace mapfuse::lidar
