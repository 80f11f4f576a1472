#include "spatial_index.hpp"

#include <algorithm>
#include <cmath>

#include "mapfuse/core/voxel_grid.hpp"

namespace mapfuse::update {

ElementIndex::ElementIndex(const VectorMap& map, double reach, double cell) : cell_(cell) {
  for (std::size_t e = 0; e < map.instances.size(); ++e) {
    const auto& pts = map.instances[e].points;
    if (pts.empty()) continue;
    Eigen::Vector2d lo = pts.front().head<2>(), hi = lo;
    for (const auto& p : pts) lo = lo.cwiseMin(p.head<2>()), hi = hi.cwiseMax(p.head<2>());
    const int64_t x0 = int64_t(std::floor((lo.x() - reach) / cell_));
    const int64_t x1 = int64_t(std::floor((hi.x() + reach) / cell_));
    const int64_t y0 = int64_t(std::floor((lo.y() - reach) / cell_));
    const int64_t y1 = int64_t(std::floor((hi.y() + reach) / cell_));
    for (int64_t x = x0; x <= x1; ++x)
      for (int64_t y = y0; y <= y1; ++y) cells_[voxel_grid::cellKey2d(x, y)].push_back(e);
  }
}

const std::vector<std::size_t>& ElementIndex::near(const Eigen::Vector3d& p) const {
  const auto it = cells_.find(voxel_grid::cellKey2d(p.x(), p.y(), cell_));
  return it == cells_.end() ? none_ : it->second;
}

std::vector<std::size_t> ElementIndex::within(const Eigen::Vector2d& lo,
                                              const Eigen::Vector2d& hi) const {
  std::vector<std::size_t> out;
  const int64_t x0 = int64_t(std::floor(lo.x() / cell_)), x1 = int64_t(std::floor(hi.x() / cell_));
  const int64_t y0 = int64_t(std::floor(lo.y() / cell_)), y1 = int64_t(std::floor(hi.y() / cell_));
  for (int64_t x = x0; x <= x1; ++x)
    for (int64_t y = y0; y <= y1; ++y) {
      const auto it = cells_.find(voxel_grid::cellKey2d(x, y));
      if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

SegmentIndex::SegmentIndex(const std::vector<const aggregate::Observation*>& lines, double search)
    : cell_(search) {
  for (const auto* o : lines)
    for (std::size_t i = 0; i + 1 < o->points.size(); ++i) {
      const Segment s{o->points[i].head<2>(), o->points[i + 1].head<2>(),
                      o->attributes.style == LineStyle::kDashed};
      // listed in every cell it passes (sampled every half cell), so that the 3 x 3 cells
      // around a sample hold every segment within `search` of it
      const int n = std::max(1, int(std::ceil((s.b - s.a).norm() / (0.5 * cell_))));
      int64_t last = 0;
      for (int k = 0; k <= n; ++k) {
        const Eigen::Vector2d q = s.a + (s.b - s.a) * (double(k) / n);
        const int64_t c = key(cellOf(q.x()), cellOf(q.y()));
        if (k > 0 && c == last) continue;
        auto& list = cells_[c];
        if (list.empty() || list.back() != segments_.size()) list.push_back(segments_.size());
        last = c;
      }
      segments_.push_back(s);
    }
}

int64_t SegmentIndex::cellOf(double v) const {
  return int64_t(std::floor(v / cell_));
}

int64_t SegmentIndex::key(int64_t ix, int64_t iy) {
  return voxel_grid::cellKey2d(ix, iy);
}

}  // namespace mapfuse::update
