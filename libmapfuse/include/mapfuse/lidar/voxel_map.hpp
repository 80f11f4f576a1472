#pragma once
/// @file The semantic voxel map (Jeong et al. 2018, §2.1): hashed voxels with integer keys in a
/// flat open-addressing table (no per-voxel heap allocation, 48 bytes per voxel in fixed-size
/// pages plus 6-12 bytes of index), each holding the normalised log posterior of the 8 LiDAR
/// classes, fused recursively (eq. 5-6) in log space. New voxels start uniform.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/lidar/paged_array.hpp"

namespace mapfuse::lidar {

/// A class distribution over the 8 LiDAR classes (probabilities, summing to 1).
using ClassDistribution = std::array<float, kNumLidarClasses>;

/// Integer voxel coordinates, each within [-2^20, 2^20) (±52 km at 5 cm).
struct VoxelCoord {
  int32_t x, y, z;
};

/// One voxel: 48 bytes, trivially copyable.
struct Voxel {
  uint64_t key;                      ///< packed VoxelCoord
  float log_prob[kNumLidarClasses];  ///< normalised log posterior (nats)
  uint32_t observations;             ///< fused measurements
  uint8_t label;                     ///< argmax of log_prob (LidarClass)
  uint8_t reserved[3];
};
static_assert(sizeof(Voxel) == 48, "Voxel layout");

/// @brief Packs voxel coordinates into a 63-bit key. @throws InputError when out of range.
uint64_t packKey(const VoxelCoord& c);
/// @brief Inverse of packKey.
VoxelCoord unpackKey(uint64_t key);

class SemanticVoxelMap {
 public:
  /// @param voxel_size voxel edge (m, > 0)
  /// @param min_log_prob floor of each class's log posterior (nats, < 0) so that the map can
  ///        still change its mind after many agreeing observations
  explicit SemanticVoxelMap(double voxel_size = 0.05, float min_log_prob = -20.0f);

  double voxelSize() const { return voxel_size_; }
  std::size_t size() const { return voxels_.size(); }
  bool empty() const { return voxels_.empty(); }
  /// Voxels in insertion order (indexable, iterable; paged, so not contiguous).
  const PagedArray<Voxel>& voxels() const { return voxels_; }

  /// @brief Integer coordinates of the voxel containing p (floor(p / size)).
  VoxelCoord coordOf(const Eigen::Vector3d& p) const;
  /// @brief Centre of a voxel (m).
  Eigen::Vector3d center(uint64_t key) const;

  /// @brief Index of the voxel with `key`, or -1.
  int64_t find(uint64_t key) const;
  /// @brief Index of the voxel with `key`, inserting a uniform voxel when absent.
  std::size_t findOrInsert(uint64_t key);

  /// @brief eq. (5)-(6): log P(l | z_1:t) = log P(z_t | l) + log P(l | z_1:t-1) - log eta,
  /// with the measurement likelihood P(z_t | l) = `measurement` (floored at min_probability
  /// inside the caller), then renormalised by log-sum-exp; updates the argmax label.
  void fuse(std::size_t index, const ClassDistribution& measurement);

  /// @brief Posterior probability of the voxel's argmax label.
  float confidence(std::size_t index) const;

  /// @brief Keeps only voxels with keep[i] != 0 (order preserved) and rebuilds the index.
  void filter(const std::vector<uint8_t>& keep);

  /// @brief Reserves storage for n voxels.
  void reserve(std::size_t n);

  /// @brief Releases unused voxel-array capacity (after building the map; at most one page).
  void shrinkToFit() { voxels_.shrinkToFit(); }

  /// @brief Heap bytes held (voxel array capacity + index table).
  std::size_t memoryBytes() const;

  /// @brief Adds a voxel as is (used by readers and tests).
  void insertVoxel(const Voxel& v);

 private:
  void rehash(std::size_t capacity);
  double voxel_size_, inv_voxel_size_;
  float min_log_prob_;
  PagedArray<Voxel> voxels_;     ///< grows page by page: no old+new copy at the memory peak
  std::vector<uint32_t> table_;  ///< voxel index + 1, 0 = empty; power-of-two size
  uint64_t mask_ = 0;
};

}  // namespace mapfuse::lidar
