#include "mapfuse/lidar/local_voxel_map.hpp"

#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/voxel_grid.hpp"

namespace mapfuse::lidar {
namespace {
constexpr uint32_t kEmpty = ~0u;
}  // namespace

LocalVoxelMap::LocalVoxelMap(const LocalMapSettings& s) : s_(s) {
  if (!(s.voxel_size > 0) || s.max_points_per_voxel < 1 || s.max_points_per_voxel > 255 ||
      !(s.max_distance > 0))
    throw ConfigError(
        "LocalMapSettings: voxel_size > 0, max_points_per_voxel in 1..255 and max_distance > 0 "
        "are required");
  inv_voxel_ = 1.0 / s.voxel_size;
  min_spacing_sq_ = s.voxel_size * s.voxel_size / s.max_points_per_voxel;
  rebuildTable(1024);
}

std::size_t LocalVoxelMap::numPoints() const {
  std::size_t n = 0;
  for (uint8_t c : counts_) n += c;
  return n;
}

std::vector<Eigen::Vector3d> LocalVoxelMap::points() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(numPoints());
  const std::size_t m = static_cast<std::size_t>(s_.max_points_per_voxel);
  for (std::size_t v = 0; v < keys_.size(); ++v)
    for (std::size_t i = 0; i < counts_[v]; ++i) out.push_back(points_[v * m + i]);
  return out;
}

int LocalVoxelMap::findVoxel(uint64_t key) const {
  uint64_t h = voxel_grid::mix(key) & mask_;
  while (true) {
    const uint32_t v = table_[h];
    if (v == kEmpty) return -1;
    if (keys_[v] == key) return static_cast<int>(v);
    h = (h + 1) & mask_;
  }
}

void LocalVoxelMap::insertSlot(uint64_t key, uint32_t voxel) {
  uint64_t h = voxel_grid::mix(key) & mask_;
  while (table_[h] != kEmpty) h = (h + 1) & mask_;
  table_[h] = voxel;
}

void LocalVoxelMap::rebuildTable(std::size_t min_capacity) {
  std::size_t capacity = 1024;
  while (capacity < min_capacity || capacity < 2 * keys_.size()) capacity <<= 1;
  table_.assign(capacity, kEmpty);
  mask_ = capacity - 1;
  for (std::size_t v = 0; v < keys_.size(); ++v) insertSlot(keys_[v], static_cast<uint32_t>(v));
}

void LocalVoxelMap::update(const std::vector<Eigen::Vector3d>& points,
                           const std::vector<Eigen::Vector3d>& normals,
                           const Eigen::Vector3d& origin) {
  if (normals.size() != points.size())
    throw InputError("LocalVoxelMap::update: points and normals differ in size");
  update(
      points, [&](std::size_t i) { return normals[i]; }, origin);
}

void LocalVoxelMap::update(const std::vector<Eigen::Vector3d>& points,
                           const std::function<Eigen::Vector3d(std::size_t)>& normal_of,
                           const Eigen::Vector3d& origin) {
  const std::size_t m = static_cast<std::size_t>(s_.max_points_per_voxel);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    const uint64_t key = voxel_grid::pointKey(p, inv_voxel_);
    const int found = findVoxel(key);
    if (found < 0) {
      const uint32_t v = static_cast<uint32_t>(keys_.size());
      keys_.push_back(key);
      counts_.push_back(1);
      points_.resize(points_.size() + m, Eigen::Vector3d::Zero());
      normals_.resize(normals_.size() + m, Eigen::Vector3d::Zero());
      points_[v * m] = p;
      normals_[v * m] = normal_of(i);
      if (2 * keys_.size() > table_.size())
        rebuildTable(2 * table_.size());
      else
        insertSlot(key, v);
      continue;
    }
    const std::size_t v = static_cast<std::size_t>(found);
    const std::size_t n = counts_[v];
    if (n >= m) continue;
    bool crowded = false;
    for (std::size_t i = 0; i < n && !crowded; ++i)
      crowded = (points_[v * m + i] - p).squaredNorm() < min_spacing_sq_;
    if (crowded) continue;
    points_[v * m + n] = p;
    normals_[v * m + n] = normal_of(i);
    ++counts_[v];
  }
  // Drop voxels far from the sensor (their first point decides, as in kiss-icp), keeping order.
  const double max_sq = s_.max_distance * s_.max_distance;
  std::size_t kept = 0;
  for (std::size_t v = 0; v < keys_.size(); ++v) {
    if ((points_[v * m] - origin).squaredNorm() >= max_sq) continue;
    if (kept != v) {
      keys_[kept] = keys_[v];
      counts_[kept] = counts_[v];
      for (std::size_t i = 0; i < m; ++i) {
        points_[kept * m + i] = points_[v * m + i];
        normals_[kept * m + i] = normals_[v * m + i];
      }
    }
    ++kept;
  }
  if (kept != keys_.size()) {
    keys_.resize(kept);
    counts_.resize(kept);
    points_.resize(kept * m);
    normals_.resize(kept * m);
    rebuildTable(table_.size() / 2);
  }
}

bool LocalVoxelMap::nearest(const Eigen::Vector3d& q, double max_dist_sq, MapNeighbor* out) const {
  const double size = s_.voxel_size;
  const double fx = std::floor(q.x() * inv_voxel_), fy = std::floor(q.y() * inv_voxel_),
               fz = std::floor(q.z() * inv_voxel_);
  const int64_t cx = int64_t(fx), cy = int64_t(fy), cz = int64_t(fz);
  const double lx = q.x() - fx * size, ly = q.y() - fy * size, lz = q.z() - fz * size;
  const std::size_t m = static_cast<std::size_t>(s_.max_points_per_voxel);
  double best = max_dist_sq;
  std::size_t best_i = 0;
  int best_v = -1;
  for (const voxel_grid::CellOffset& o : voxel_grid::kNeighbourOrder) {
    const double gx = voxel_grid::axisGap(o.dx, lx, size), gy = voxel_grid::axisGap(o.dy, ly, size),
                 gz = voxel_grid::axisGap(o.dz, lz, size);
    if (gx * gx + gy * gy + gz * gz >= best) continue;
    const int v = findVoxel(voxel_grid::pack(cx + o.dx, cy + o.dy, cz + o.dz));
    if (v < 0) continue;
    const std::size_t base = static_cast<std::size_t>(v) * m;
    for (std::size_t i = base; i < base + counts_[static_cast<std::size_t>(v)]; ++i) {
      const double d = (points_[i] - q).squaredNorm();
      if (d < best) {
        best = d;
        best_i = i;
        best_v = v;
      }
    }
  }
  if (best_v < 0) return false;
  out->point = points_[best_i];
  out->normal = normals_[best_i];
  out->dist_sq = best;
  out->voxel = best_v;
  return true;
}

}  // namespace mapfuse::lidar
