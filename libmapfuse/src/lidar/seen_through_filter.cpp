#include "mapfuse/lidar/seen_through_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mapfuse/core/angles.hpp"
#include "mapfuse/core/error.hpp"

namespace mapfuse::lidar {

namespace {
constexpr float kNoReturn = std::numeric_limits<float>::infinity();
constexpr double kMinPointRange = 0.5;  // m, returns from the vehicle itself are ignored
constexpr double kColumnSize = 10.0;    // m, (x, y) cells of the per-scan voxel culling

// Classes whose voxels rays graze (ground) or slip past (thin, porous): tested with the wider
// window, so that a ray passing beside a pole or through a hedge does not clear it.
bool isThinOrGround(LidarClass c) {
  return c == LidarClass::kRoad || c == LidarClass::kSidewalk || c == LidarClass::kFence ||
         c == LidarClass::kPole || c == LidarClass::kVegetation;
}
}  // namespace

SeenThroughFilter::SeenThroughFilter(const SemanticVoxelMap& map, const SeenThroughSettings& s,
                                     const SensorReach& reach, int num_threads)
    : s_(s), reach_(reach), num_threads_(std::max(1, num_threads)), map_(&map) {
  if (!(s.azimuth_resolution_deg > 0) || !(s.elevation_resolution_deg > 0))
    throw InputError("seen-through filter: range-image resolutions must be > 0");
  if (!(s.elevation_max_deg > s.elevation_min_deg))
    throw InputError("seen-through filter: elevation_max_deg must exceed elevation_min_deg");
  if (!(s.margin > 0) || s.window < 0 || s.window_thin < 0 || !(reach.max_range > reach.min_range))
    throw InputError("seen-through filter: margin > 0, windows >= 0, max_range > min_range");
  if (!(s.vehicle_vote_radius >= 0) || !(s.vehicle_vote_share > 0 && s.vehicle_vote_share <= 1))
    throw InputError("seen-through filter: vehicle_vote_radius >= 0, vehicle_vote_share in (0, 1]");
  cols_ = static_cast<int>(std::ceil(360.0 / s.azimuth_resolution_deg));
  rows_ = static_cast<int>(
      std::ceil((s.elevation_max_deg - s.elevation_min_deg) / s.elevation_resolution_deg));
  through_.assign(map.size(), 0);
  hit_.assign(map.size(), 0);
  // Voxel indices grouped by (x, y) column, so that each scan visits only nearby columns.
  const auto& voxels = map.voxels();
  std::vector<std::pair<uint64_t, uint32_t>> keyed(voxels.size());
  for (std::size_t i = 0; i < voxels.size(); ++i)
    keyed[i] = {columnKey(map.center(voxels[i].key)), static_cast<uint32_t>(i)};
  std::sort(keyed.begin(), keyed.end());
  order_.resize(keyed.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    order_[i] = keyed[i].second;
    if (i == 0 || keyed[i].first != keyed[i - 1].first)
      columns_.push_back({keyed[i].first, static_cast<uint32_t>(i), 0});
    columns_.back().end = static_cast<uint32_t>(i + 1);
  }
}

uint64_t SeenThroughFilter::columnKey(const Eigen::Vector3d& p) {
  const auto ix = static_cast<int64_t>(std::floor(p.x() / kColumnSize)) + (int64_t(1) << 31);
  const auto iy = static_cast<int64_t>(std::floor(p.y() / kColumnSize)) + (int64_t(1) << 31);
  return (static_cast<uint64_t>(ix) << 32) | (static_cast<uint64_t>(iy) & 0xffffffffull);
}

void SeenThroughFilter::addScan(const std::vector<Eigen::Vector3f>& scan_velo,
                                const Pose3& T_map_velo) {
  ++scans_;
  if (through_.empty()) return;
  const double az_scale = 1.0 / (s_.azimuth_resolution_deg * kDegree);
  const double el_scale = 1.0 / (s_.elevation_resolution_deg * kDegree);
  const double el_min = s_.elevation_min_deg * kDegree;
  auto pixel = [&](const Eigen::Vector3d& p, double r, int* row, int* col) {
    const double el = std::asin(std::clamp(p.z() / r, -1.0, 1.0));
    *row = static_cast<int>(std::floor((el - el_min) * el_scale));
    if (*row < 0 || *row >= rows_) return false;
    *col = static_cast<int>(std::floor((std::atan2(p.y(), p.x()) + kPi) * az_scale)) % cols_;
    return true;
  };
  // Range image: the nearest return per pixel.
  image_.assign(static_cast<std::size_t>(cols_) * rows_, kNoReturn);
  for (const auto& pf : scan_velo) {
    const Eigen::Vector3d p = pf.cast<double>();
    const double r = p.norm();
    int row, col;
    if (!(r > kMinPointRange) || !pixel(p, r, &row, &col)) continue;
    float& cell = image_[static_cast<std::size_t>(row) * cols_ + col];
    cell = std::min(cell, static_cast<float>(r));
  }
  const Pose3 T_velo_map = T_map_velo.inverse();
  // Columns within max_range of the sensor (in x and y).
  std::vector<const Column*> near;
  const Eigen::Vector3d c = T_map_velo.translation();
  const int reach = static_cast<int>(std::ceil(reach_.max_range / kColumnSize));
  for (int dx = -reach; dx <= reach; ++dx)
    for (int dy = -reach; dy <= reach; ++dy) {
      const uint64_t key = columnKey(c + Eigen::Vector3d(dx * kColumnSize, dy * kColumnSize, 0.0));
      const auto it = std::lower_bound(columns_.begin(), columns_.end(), key,
                                       [](const Column& col, uint64_t k) { return col.key < k; });
      if (it != columns_.end() && it->key == key) near.push_back(&*it);
    }
  const auto& voxels = map_->voxels();

#pragma omp parallel for schedule(dynamic, 4) num_threads(num_threads_)
  for (std::size_t n = 0; n < near.size(); ++n)
    for (uint32_t o = near[n]->begin; o < near[n]->end; ++o) {
      const std::size_t k = order_[o];
      const Voxel& v = voxels[k];
      const Eigen::Vector3d q = T_velo_map * map_->center(v.key);
      const double r = q.norm();
      int row, col;
      if (r < reach_.min_range || r > reach_.max_range || !pixel(q, r, &row, &col)) continue;
      float nearest = kNoReturn;
      const int w = isThinOrGround(static_cast<LidarClass>(v.label)) ? s_.window_thin : s_.window;
      for (int dr = -w; dr <= w; ++dr) {
        const int rr = row + dr;
        if (rr < 0 || rr >= rows_) continue;
        for (int dc = -w; dc <= w; ++dc) {
          const int cc = (col + dc + cols_) % cols_;
          nearest = std::min(nearest, image_[static_cast<std::size_t>(rr) * cols_ + cc]);
        }
      }
      if (nearest == kNoReturn) continue;  // no return around: no evidence either way
      if (nearest > r + s_.margin) {
        if (through_[k] < UINT16_MAX) ++through_[k];
      } else if (nearest > r - s_.margin) {
        if (hit_[k] < UINT16_MAX) ++hit_[k];
      }  // else occluded by something nearer
    }
}

std::vector<uint8_t> SeenThroughFilter::keepMask(SeenThroughStats* stats) const {
  std::vector<uint8_t> keep(through_.size(), 1);
  for (std::size_t k = 0; k < through_.size(); ++k) {
    const int seen = through_[k] + hit_[k];
    if (through_[k] >= s_.min_seen_through && through_[k] >= s_.min_free_ratio * seen) keep[k] = 0;
  }
  if (s_.vehicle_vote_radius > 0) voteOverVehicles(keep);
  if (stats)
    *stats = {through_.size(), scans_,
              static_cast<std::size_t>(std::count(keep.begin(), keep.end(), uint8_t{0}))};
  return keep;
}

void SeenThroughFilter::voteOverVehicles(std::vector<uint8_t>& keep) const {
  // Vehicle voxels per (x, y) cell of the voxel grid: how many, how many seen through.
  struct Cell {
    int32_t x, y;
    uint32_t through, total;
  };
  const auto& voxels = map_->voxels();
  const auto vehicle = static_cast<uint8_t>(LidarClass::kVehicle);
  std::vector<Cell> cells;
  for (std::size_t k = 0; k < voxels.size(); ++k)
    if (voxels[k].label == vehicle) {
      const VoxelCoord c = unpackKey(voxels[k].key);
      cells.push_back({c.x, c.y, keep[k] ? 0u : 1u, 1u});
    }
  auto before = [](const Cell& a, const Cell& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; };
  std::sort(cells.begin(), cells.end(), before);
  std::size_t n = 0;  // merge the voxels of one column
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (n > 0 && cells[n - 1].x == cells[i].x && cells[n - 1].y == cells[i].y) {
      cells[n - 1].through += cells[i].through;
      cells[n - 1].total += cells[i].total;
    } else {
      cells[n++] = cells[i];
    }
  }
  cells.resize(n);
  // Verdict per cell: the share of seen-through vehicle voxels in the disc around it.
  const double rc = s_.vehicle_vote_radius / map_->voxelSize();
  const int reach = static_cast<int>(std::floor(rc));
  std::vector<uint8_t> goes(cells.size(), 0);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    uint64_t through = 0, total = 0;
    for (int dx = -reach; dx <= reach; ++dx) {
      const int dy = static_cast<int>(std::floor(std::sqrt(rc * rc - double(dx) * dx)));
      auto it = std::lower_bound(cells.begin(), cells.end(),
                                 Cell{cells[i].x + dx, cells[i].y - dy, 0, 0}, before);
      for (; it != cells.end() && it->x == cells[i].x + dx && it->y <= cells[i].y + dy; ++it) {
        through += it->through;
        total += it->total;
      }
    }
    goes[i] = static_cast<double>(through) >= s_.vehicle_vote_share * static_cast<double>(total);
  }
  for (std::size_t k = 0; k < voxels.size(); ++k)
    if (voxels[k].label == vehicle) {
      const VoxelCoord c = unpackKey(voxels[k].key);
      const auto it = std::lower_bound(cells.begin(), cells.end(), Cell{c.x, c.y, 0, 0}, before);
      keep[k] = goes[static_cast<std::size_t>(it - cells.begin())] ? 0 : 1;
    }
}

}  // namespace mapfuse::lidar
