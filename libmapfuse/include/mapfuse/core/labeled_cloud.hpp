#pragma once
/// @file A labelled point cloud: what the semantic voxel map exports (voxel centres with their
/// argmax LiDAR class and its posterior probability) and what the PLY / PCD writers take.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace mapfuse {

struct LabeledCloud {
  std::vector<Eigen::Vector3f> points;  ///< m, map frame
  std::vector<uint8_t> labels;          ///< LidarClass per point (core/classes.hpp)
  std::vector<float> confidence;        ///< posterior of the label, 0..1
  std::size_t size() const { return points.size(); }
};

}  // namespace mapfuse
