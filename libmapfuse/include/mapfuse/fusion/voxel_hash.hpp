#pragma once
/// @file Voxel-hash nearest-neighbour index (kiss-icp / small_gicp style): integer voxel keys in a
/// flat open-addressing table, points stored contiguously per voxel, queries visit the 27 voxels
/// around the query. Exact for radii up to the cell size.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mapfuse::fusion {

/// @brief Packs integer voxel coordinates (each in [-2^20, 2^20)) into one 63-bit key.
uint64_t packVoxelKey(int64_t x, int64_t y, int64_t z);

/// @brief Voxel coordinates (floor(p / size)) packed as a key.
uint64_t voxelKey(const Eigen::Vector3d& p, double inv_cell_size);

class VoxelIndex {
 public:
  VoxelIndex() = default;
  /// @param points indexed points (copied, reordered by voxel)
  /// @param cell_size voxel edge, m (> 0); queries are exact within this radius
  VoxelIndex(const std::vector<Eigen::Vector3d>& points, double cell_size);

  /// @brief Nearest point within sqrt(max_dist_sq) (<= cell size for exactness).
  /// @return original index of the point, or -1; *dist_sq receives its squared distance.
  int nearest(const Eigen::Vector3d& q, double max_dist_sq, double* dist_sq) const;

  /// @brief Up to k nearest points among the 27 cells around q, sorted by distance.
  /// @return number found (<= k); idx / dist_sq must hold k entries.
  int knn(const Eigen::Vector3d& q, int k, int* idx, double* dist_sq) const;

  /// @brief Calls f(original index, squared distance) for every point nearer than
  /// sqrt(max_dist_sq) (<= cell size for completeness) of q, in no particular order.
  template <class F>
  void forEachWithin(const Eigen::Vector3d& q, double max_dist_sq, F&& f) const;
  double cellSize() const { return cell_size_; }
  std::size_t size() const { return points_.size(); }

 private:
  struct Slot {
    uint64_t key = ~0ull;  ///< ~0 = empty
    uint32_t begin = 0, end = 0;
  };
  const Slot* find(uint64_t key) const;

  double cell_size_ = 1.0, inv_cell_size_ = 1.0;
  std::vector<Eigen::Vector3d> points_;  ///< sorted by voxel
  std::vector<int> original_;            ///< original index of points_[i]
  std::vector<Slot> table_;
  uint64_t mask_ = 0;
};

template <class F>
void VoxelIndex::forEachWithin(const Eigen::Vector3d& q, double max_dist_sq, F&& f) const {
  const int64_t cx = static_cast<int64_t>(std::floor(q.x() * inv_cell_size_));
  const int64_t cy = static_cast<int64_t>(std::floor(q.y() * inv_cell_size_));
  const int64_t cz = static_cast<int64_t>(std::floor(q.z() * inv_cell_size_));
  for (int64_t dx = -1; dx <= 1; ++dx)
    for (int64_t dy = -1; dy <= 1; ++dy)
      for (int64_t dz = -1; dz <= 1; ++dz) {
        const Slot* s = find(packVoxelKey(cx + dx, cy + dy, cz + dz));
        if (!s) continue;
        for (uint32_t i = s->begin; i < s->end; ++i) {
          const double d = (points_[i] - q).squaredNorm();
          if (d < max_dist_sq) f(original_[i], d);
        }
      }
}

}  // namespace mapfuse::fusion
