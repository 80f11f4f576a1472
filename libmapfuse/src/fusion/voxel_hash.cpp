#include "mapfuse/fusion/voxel_hash.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/voxel_grid.hpp"

namespace mapfuse::fusion {

uint64_t packVoxelKey(int64_t x, int64_t y, int64_t z) {
  return voxel_grid::pack(x, y, z);
}

uint64_t voxelKey(const Eigen::Vector3d& p, double inv_cell_size) {
  return voxel_grid::pointKey(p, inv_cell_size);
}

VoxelIndex::VoxelIndex(const std::vector<Eigen::Vector3d>& points, double cell_size)
    : cell_size_(cell_size), inv_cell_size_(1.0 / cell_size) {
  if (!(cell_size > 0.0)) throw InputError("VoxelIndex: cell size must be > 0");
  const std::size_t n = points.size();
  std::vector<std::pair<uint64_t, int>> keyed(n);
  for (std::size_t i = 0; i < n; ++i) keyed[i] = {voxelKey(points[i], inv_cell_size_), int(i)};
  std::sort(keyed.begin(), keyed.end());
  points_.resize(n);
  original_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    points_[i] = points[keyed[i].second];
    original_[i] = keyed[i].second;
  }
  std::size_t voxels = 0;
  for (std::size_t i = 0; i < n; ++i) voxels += (i == 0 || keyed[i].first != keyed[i - 1].first);
  std::size_t capacity = 16;
  while (capacity < 2 * voxels) capacity <<= 1;
  table_.assign(capacity, Slot{});
  mask_ = capacity - 1;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j < n && keyed[j].first == keyed[i].first) ++j;
    uint64_t h = voxel_grid::mix(keyed[i].first) & mask_;
    while (table_[h].key != ~0ull) h = (h + 1) & mask_;
    table_[h] = Slot{keyed[i].first, uint32_t(i), uint32_t(j)};
    i = j;
  }
}

const VoxelIndex::Slot* VoxelIndex::find(uint64_t key) const {
  if (table_.empty()) return nullptr;
  uint64_t h = voxel_grid::mix(key) & mask_;
  while (true) {
    const Slot& s = table_[h];
    if (s.key == key) return &s;
    if (s.key == ~0ull) return nullptr;
    h = (h + 1) & mask_;
  }
}

using voxel_grid::axisGap;
using CellVisit = voxel_grid::CellOffset;
constexpr const auto& kCellOrder = voxel_grid::kNeighbourOrder;

int VoxelIndex::nearest(const Eigen::Vector3d& q, double max_dist_sq, double* dist_sq) const {
  const double fx = std::floor(q.x() * inv_cell_size_), fy = std::floor(q.y() * inv_cell_size_),
               fz = std::floor(q.z() * inv_cell_size_);
  const int64_t cx = int64_t(fx), cy = int64_t(fy), cz = int64_t(fz);
  const double lx = q.x() - fx * cell_size_, ly = q.y() - fy * cell_size_,
               lz = q.z() - fz * cell_size_;
  int best = -1;
  double best_d = max_dist_sq;
  for (const CellVisit& c : kCellOrder) {
    const double gx = axisGap(c.dx, lx, cell_size_), gy = axisGap(c.dy, ly, cell_size_),
                 gz = axisGap(c.dz, lz, cell_size_);
    if (gx * gx + gy * gy + gz * gz >= best_d) continue;
    const Slot* s = find(packVoxelKey(cx + c.dx, cy + c.dy, cz + c.dz));
    if (!s) continue;
    for (uint32_t i = s->begin; i < s->end; ++i) {
      const double d = (points_[i] - q).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = int(i);
      }
    }
  }
  if (best < 0) return -1;
  if (dist_sq) *dist_sq = best_d;
  return original_[best];
}

int VoxelIndex::knn(const Eigen::Vector3d& q, int k, int* idx, double* dist_sq) const {
  const int64_t cx = static_cast<int64_t>(std::floor(q.x() * inv_cell_size_));
  const int64_t cy = static_cast<int64_t>(std::floor(q.y() * inv_cell_size_));
  const int64_t cz = static_cast<int64_t>(std::floor(q.z() * inv_cell_size_));
  const double lx = q.x() - double(cx) * cell_size_, ly = q.y() - double(cy) * cell_size_,
               lz = q.z() - double(cz) * cell_size_;
  int found = 0;
  for (const CellVisit& c : kCellOrder) {
    const double gx = axisGap(c.dx, lx, cell_size_), gy = axisGap(c.dy, ly, cell_size_),
                 gz = axisGap(c.dz, lz, cell_size_);
    if (found == k && gx * gx + gy * gy + gz * gz >= dist_sq[k - 1]) continue;
    const Slot* s = find(packVoxelKey(cx + c.dx, cy + c.dy, cz + c.dz));
    if (!s) continue;
    for (uint32_t i = s->begin; i < s->end; ++i) {
      const double d = (points_[i] - q).squaredNorm();
      if (found == k && d >= dist_sq[k - 1]) continue;
      // insertion into the sorted k-list
      int pos = found < k ? found++ : k - 1;
      while (pos > 0 && dist_sq[pos - 1] > d) {
        dist_sq[pos] = dist_sq[pos - 1];
        idx[pos] = idx[pos - 1];
        --pos;
      }
      dist_sq[pos] = d;
      idx[pos] = int(i);
    }
  }
  for (int i = 0; i < found; ++i) idx[i] = original_[idx[i]];
  return found;
}

}  // namespace mapfuse::fusion
