#pragma once
/// @file The bounded local map of the LiDAR odometry (after kiss-icp's VoxelHashMap, Vizzo et al.
/// 2023): registered points in the odometry frame, at most `max_points_per_voxel` per voxel and at
/// least sqrt(voxel^2 / max_points_per_voxel) apart, voxels farther than `max_distance` from the
/// sensor dropped after every update. Its size, and so the cost of a scan, is bounded however long
/// the drive. Integer voxel keys in a flat open-addressing table; nearest-neighbour queries visit
/// the 27 voxels around the query, skipping those farther than the best point found so far. Every
/// point carries the normal of its surface, estimated in the scan it came from (zero: none).
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

namespace mapfuse::lidar {

struct LocalMapSettings {
  double voxel_size = 1.0;        ///< m, voxel edge (also the exact nearest-neighbour radius)
  int max_points_per_voxel = 20;  ///< points kept per voxel (>= 1)
  double max_distance = 100.0;    ///< m, voxels whose first point is farther from the sensor go
};

/// A nearest-neighbour answer: the map point, its normal, its squared distance and its voxel.
struct MapNeighbor {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< m, odometry frame
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit, or zero when the point has none
  double dist_sq = 0.0;                              ///< m^2
  int voxel = -1;                                    ///< voxel index, -1: none
};

class LocalVoxelMap {
 public:
  /// @throws ConfigError when a setting is out of range (voxel_size > 0, max points >= 1,
  /// max_distance > 0).
  explicit LocalVoxelMap(const LocalMapSettings& settings);

  /// @brief Adds points (odometry frame) with their unit normals (same size, zero = none), then
  /// drops voxels farther than max_distance from `origin` (the sensor, odometry frame).
  /// @throws InputError when the sizes differ.
  void update(const std::vector<Eigen::Vector3d>& points,
              const std::vector<Eigen::Vector3d>& normals, const Eigen::Vector3d& origin);

  /// @brief The same with the normal of point i asked for only when the point is kept.
  void update(const std::vector<Eigen::Vector3d>& points,
              const std::function<Eigen::Vector3d(std::size_t)>& normal_of,
              const Eigen::Vector3d& origin);

  /// @brief Nearest map point to q within sqrt(max_dist_sq) (exact up to one voxel edge).
  /// @return false when there is none.
  bool nearest(const Eigen::Vector3d& q, double max_dist_sq, MapNeighbor* out) const;

  bool empty() const { return keys_.empty(); }
  std::size_t numVoxels() const { return keys_.size(); }
  std::size_t numPoints() const;
  /// @brief Every map point (for tests and pictures).
  std::vector<Eigen::Vector3d> points() const;
  const LocalMapSettings& settings() const { return s_; }

 private:
  int findVoxel(uint64_t key) const;
  void insertSlot(uint64_t key, uint32_t voxel);
  void rebuildTable(std::size_t min_capacity);

  LocalMapSettings s_;
  double inv_voxel_ = 1.0;
  double min_spacing_sq_ = 0.0;           ///< m^2, closer points are not added to a voxel
  std::vector<uint64_t> keys_;            ///< per voxel
  std::vector<uint8_t> counts_;           ///< per voxel
  std::vector<Eigen::Vector3d> points_;   ///< max_points_per_voxel slots per voxel
  std::vector<Eigen::Vector3d> normals_;  ///< the same slots
  std::vector<uint32_t> table_;           ///< open addressing: voxel index, ~0u = empty
  uint64_t mask_ = 0;
};

}  // namespace mapfuse::lidar
