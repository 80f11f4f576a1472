#include "mapfuse/lidar/error_minimization.hpp"

namespace mapfuse::lidar {

std::vector<LabeledCluster> labelClusters(const std::vector<Eigen::Vector3f>& points,
                                          const std::vector<uint8_t>& labels,
                                          const ClusteringSettings& settings,
                                          const std::array<bool, kNumLidarClasses>& mask) {
  std::vector<LabeledCluster> out;
  std::array<std::vector<int>, kNumLidarClasses> by_label;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (labels[i] < kNumLidarClasses && mask[labels[i]])
      by_label[labels[i]].push_back(static_cast<int>(i));
  for (int l = 0; l < kNumLidarClasses; ++l) {
    const auto& idx = by_label[l];
    if (idx.empty()) continue;
    std::vector<Eigen::Vector3f> sub(idx.size());
    for (std::size_t k = 0; k < idx.size(); ++k) sub[k] = points[idx[k]];
    int n = 0;
    const std::vector<int> ids = euclideanClusters(sub, settings, &n);
    const std::size_t first = out.size();
    out.resize(first + static_cast<std::size_t>(n));
    for (std::size_t k = 0; k < idx.size(); ++k)
      if (ids[k] >= 0) out[first + static_cast<std::size_t>(ids[k])].members.push_back(idx[k]);
    for (std::size_t c = first; c < out.size(); ++c) {
      out[c].label = static_cast<uint8_t>(l);
      out[c].features = clusterFeatures(points, out[c].members);
    }
  }
  return out;
}

std::vector<uint8_t> minimizeErrors(const std::vector<Eigen::Vector3f>& points,
                                    const std::vector<uint8_t>& labels,
                                    const ClusterClassifier& classifier,
                                    const ClusteringSettings& settings,
                                    ErrorMinimizationStats* stats) {
  std::vector<uint8_t> keep(points.size(), 1);
  std::array<bool, kNumLidarClasses> mask{};
  bool any = false;
  for (int l = 0; l < kNumLidarClasses; ++l) any |= mask[l] = classifier.has(LidarClass(l));
  if (!any) return keep;
  const auto clusters = labelClusters(points, labels, settings, mask);
  for (const auto& c : clusters) {
    if (stats) ++stats->clusters;
    if (classifier.accept(static_cast<LidarClass>(c.label), c.features)) continue;
    for (int i : c.members) keep[i] = 0;
    if (stats) {
      ++stats->rejected_clusters;
      stats->rejected_points += c.members.size();
    }
  }
  return keep;
}

}  // namespace mapfuse::lidar
