#pragma once
/// @file Integer voxel keys of the LiDAR odometry, inline (the per-point hot path): the packing of
/// fusion/voxel_hash.hpp (21 bits per axis, offset 2^20), computed in place.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace mapfuse::lidar::detail {

inline uint64_t packKey(int64_t x, int64_t y, int64_t z) {
  constexpr int64_t kOffset = int64_t(1) << 20;
  constexpr uint64_t kMask = (uint64_t(1) << 21) - 1;
  return (uint64_t(x + kOffset) & kMask) | ((uint64_t(y + kOffset) & kMask) << 21) |
         ((uint64_t(z + kOffset) & kMask) << 42);
}

inline uint64_t pointKey(const Eigen::Vector3d& p, double inv_cell) {
  return packKey(static_cast<int64_t>(std::floor(p.x() * inv_cell)),
                 static_cast<int64_t>(std::floor(p.y() * inv_cell)),
                 static_cast<int64_t>(std::floor(p.z() * inv_cell)));
}

/// splitmix64 finaliser: spreads packed keys over a power-of-two table.
inline uint64_t mixKey(uint64_t k) {
  k ^= k >> 31;
  k *= 0x7fb5d329728ea185ull;
  k ^= k >> 27;
  k *= 0x81dadef4bc2dd44dull;
  k ^= k >> 33;
  return k;
}

}  // namespace mapfuse::lidar::detail
