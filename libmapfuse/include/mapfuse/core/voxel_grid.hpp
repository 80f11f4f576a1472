#pragma once
/// @file Integer voxel grids shared by the nearest-neighbour indexes (fusion::VoxelIndex, the
/// LiDAR odometry's local map): 21-bit voxel coordinates packed into one key, the splitmix64
/// mixer that spreads keys over a power-of-two table, and the 27-cell search order with the
/// distance bound that lets a query skip cells farther than its best point so far.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace mapfuse::voxel_grid {

/// @brief Packs integer voxel coordinates (each in [-2^20, 2^20)) into one 63-bit key, x in the
/// low bits.
inline uint64_t pack(int64_t x, int64_t y, int64_t z) {
  constexpr int64_t kOffset = int64_t(1) << 20;
  constexpr uint64_t kMask = (uint64_t(1) << 21) - 1;
  return (uint64_t(x + kOffset) & kMask) | ((uint64_t(y + kOffset) & kMask) << 21) |
         ((uint64_t(z + kOffset) & kMask) << 42);
}

/// @brief The key of the voxel holding p: floor(p / size), with inv_cell = 1 / size.
inline uint64_t pointKey(const Eigen::Vector3d& p, double inv_cell) {
  return pack(static_cast<int64_t>(std::floor(p.x() * inv_cell)),
              static_cast<int64_t>(std::floor(p.y() * inv_cell)),
              static_cast<int64_t>(std::floor(p.z() * inv_cell)));
}

/// @brief Packs 2-D cell coordinates into one key, x in the high 32 bits (unsigned shift:
/// defined for a negative x).
inline int64_t cellKey2d(int64_t ix, int64_t iy) {
  return int64_t((uint64_t(ix) << 32) ^ (uint64_t(iy) & 0xffffffffULL));
}

/// @brief The key of the 2-D cell of side `cell` (m) holding (x, y): floor(x / cell),
/// floor(y / cell), as forEachCell2d visits them.
inline int64_t cellKey2d(double x, double y, double cell) {
  return cellKey2d(static_cast<int64_t>(std::floor(x / cell)),
                   static_cast<int64_t>(std::floor(y / cell)));
}

/// @brief splitmix64 finaliser: cheap and well mixed for packed integer keys.
inline uint64_t mix(uint64_t k) {
  k ^= k >> 31;
  k *= 0x7fb5d329728ea185ull;
  k ^= k >> 27;
  k *= 0x81dadef4bc2dd44dull;
  k ^= k >> 33;
  return k;
}

/// One of the 27 cells around a query's own cell.
struct CellOffset {
  int dx, dy, dz;
};

/// The 27 cells around the query cell: its own first, then faces, edges, corners.
inline constexpr CellOffset kNeighbourOrder[27] = {
    {0, 0, 0},   {-1, 0, 0},  {1, 0, 0},   {0, -1, 0}, {0, 1, 0},   {0, 0, -1},   {0, 0, 1},
    {-1, -1, 0}, {-1, 1, 0},  {1, -1, 0},  {1, 1, 0},  {-1, 0, -1}, {-1, 0, 1},   {1, 0, -1},
    {1, 0, 1},   {0, -1, -1}, {0, -1, 1},  {0, 1, -1}, {0, 1, 1},   {-1, -1, -1}, {-1, -1, 1},
    {-1, 1, -1}, {-1, 1, 1},  {1, -1, -1}, {1, -1, 1}, {1, 1, -1},  {1, 1, 1}};

/// @brief Calls f(ix, iy) for every cell of side `cell` (m) of a 2-D grid that the box from
/// (x_lo, y_lo) to (x_hi, y_hi) touches: floor(lo / cell) .. floor(hi / cell) on each axis, x
/// outer.
template <class F>
void forEachCell2d(double x_lo, double y_lo, double x_hi, double y_hi, double cell, F&& f) {
  const auto x0 = static_cast<int64_t>(std::floor(x_lo / cell));
  const auto x1 = static_cast<int64_t>(std::floor(x_hi / cell));
  const auto y0 = static_cast<int64_t>(std::floor(y_lo / cell));
  const auto y1 = static_cast<int64_t>(std::floor(y_hi / cell));
  for (int64_t ix = x0; ix <= x1; ++ix)
    for (int64_t iy = y0; iy <= y1; ++iy) f(ix, iy);
}

/// @brief Along one axis, the distance from a query at `local` within its cell (0..size) to the
/// neighbouring cell at offset d (-1, 0, 1): the squared sum over the axes bounds the distance
/// to any point of that cell.
inline double axisGap(int d, double local, double size) {
  return d < 0 ? local : (d > 0 ? size - local : 0.0);
}

}  // namespace mapfuse::voxel_grid
