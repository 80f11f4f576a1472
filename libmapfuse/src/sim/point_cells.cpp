#include "mapfuse/sim/point_cells.hpp"

#include <algorithm>

#include "mapfuse/core/voxel_grid.hpp"

namespace mapfuse::sim {

PointCells::PointCells(const Polyline& points, double cell) : cell_(cell) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    auto& r = ranges_[voxel_grid::cellKey2d(points[k].x(), points[k].y(), cell_)];
    if (!r.empty() && r.back().second == k)
      ++r.back().second;
    else
      r.emplace_back(static_cast<uint32_t>(k), static_cast<uint32_t>(k + 1));
  }
}

std::vector<uint32_t> PointCells::near(const Eigen::Vector3d& c, double radius) const {
  std::vector<uint32_t> out;
  voxel_grid::forEachCell2d(c.x() - radius, c.y() - radius, c.x() + radius, c.y() + radius, cell_,
                            [&](int64_t x, int64_t y) {
                              const auto it = ranges_.find(voxel_grid::cellKey2d(x, y));
                              if (it == ranges_.end()) return;
                              for (const auto& [begin, end] : it->second)
                                for (uint32_t k = begin; k < end; ++k) out.push_back(k);
                            });
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<int64_t> PointCells::cells() const {
  std::vector<int64_t> out;
  out.reserve(ranges_.size());
  for (const auto& r : ranges_) out.push_back(r.first);
  return out;
}

}  // namespace mapfuse::sim
