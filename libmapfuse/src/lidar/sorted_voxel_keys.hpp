#pragma once
/// @file The voxel keys of a map, re-packed relative to the map's bounding box into compact keys
/// that order voxels lexicographically by (x, y, z), and sorted (LSD radix sort) with the index of
/// each voxel in the map. Every (x, y) column of the map is then one contiguous run, ascending in
/// z, and the runs of neighbouring columns are near each other: the neighbours of a voxel are
/// found by short forward searches instead of random hash lookups.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mapfuse/lidar/voxel_map.hpp"

namespace mapfuse::lidar::detail {

class SortedVoxelKeys {
 public:
  explicit SortedVoxelKeys(const SemanticVoxelMap& map);

  std::size_t size() const { return keys_.size(); }
  const uint64_t* keys() const { return keys_.data(); }           ///< ascending compact keys
  uint32_t voxelIndex(std::size_t i) const { return index_[i]; }  ///< map index of keys()[i]

  /// Extent of the bounding box, voxels (coordinates relative to its lowest corner).
  int64_t nx() const { return nx_; }
  int64_t ny() const { return ny_; }
  int64_t nz() const { return nz_; }
  /// Compact key of box coordinates (0 <= x < nx, 0 <= y < ny, 0 <= z < nz).
  uint64_t key(int64_t x, int64_t y, int64_t z) const {
    return (uint64_t(x) << sx_) | (uint64_t(y) << sy_) | uint64_t(z);
  }
  int64_t x(uint64_t k) const { return int64_t(k >> sx_); }
  int64_t y(uint64_t k) const { return int64_t((k >> sy_) & my_); }
  int64_t z(uint64_t k) const { return int64_t(k & mz_); }

 private:
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> index_;
  int64_t nx_ = 0, ny_ = 0, nz_ = 0;
  int sx_ = 0, sy_ = 0;
  uint64_t my_ = 0, mz_ = 0;
};

/// @brief First i in [0, n) with k[i] >= t (n when none), for ascending k, searched outwards
/// from `hint` (exponential then binary search): O(log |result - hint|), O(1) when the result is
/// hint or hint + 1.
inline std::size_t lowerBoundFrom(const uint64_t* k, std::size_t n, std::size_t hint, uint64_t t) {
  if (hint > n) hint = n;
  std::size_t step = 1;
  if (hint < n && k[hint] < t) {  // forward: the result is in (a, a + step]
    std::size_t a = hint;
    while (a + step < n && k[a + step] < t) {
      a += step;
      step *= 2;
    }
    return std::lower_bound(k + a + 1, k + std::min(n, a + step), t) - k;
  }
  std::size_t b = hint;  // backward: k[b] >= t or b == n; the result is in (b - step, b]
  while (b >= step && k[b - step] >= t) {
    b -= step;
    step *= 2;
  }
  return std::lower_bound(k + (b >= step ? b - step + 1 : 0), k + b, t) - k;
}

}  // namespace mapfuse::lidar::detail
