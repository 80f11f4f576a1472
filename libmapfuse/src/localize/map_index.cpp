#include "mapfuse/localize/map_index.hpp"

#include <algorithm>
#include <cmath>

#include "mapfuse/core/voxel_grid.hpp"

namespace mapfuse::localize {

int matchKey(CrowdClass cls, const Attributes& attributes, bool use_attributes) {
  int key = static_cast<int>(cls) * 16;
  if (use_attributes && cls == CrowdClass::kLaneLine)
    key += static_cast<int>(attributes.style) * 4 + static_cast<int>(attributes.color);
  return key;
}

double targetDistance(const MapTarget& t, const Eigen::Vector2d& p) {
  if (!t.is_line) return (p - t.a).norm();
  const Eigen::Vector2d d = t.b - t.a;
  const double len2 = d.squaredNorm();
  const double u = len2 > 0 ? std::clamp((p - t.a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (t.a + u * d)).norm();
}

MapIndex::MapIndex(const VectorMap& map, bool use_attributes, double cell)
    : cell_(cell), use_attributes_(use_attributes) {
  for (const auto& inst : map.instances) {
    const int key = matchKey(inst.cls, inst.attributes, use_attributes);
    switch (geometryKind(inst.cls)) {
      case GeometryKind::kLine:
        for (std::size_t i = 1; i < inst.points.size(); ++i)
          insert(key, {inst.points[i - 1].head<2>(), inst.points[i].head<2>(), true});
        break;
      case GeometryKind::kPoint:
        if (!inst.points.empty())
          insert(key, {inst.points[0].head<2>(), inst.points[0].head<2>(), false});
        break;
      case GeometryKind::kPlanar: {
        if (inst.points.empty()) break;
        const Eigen::Vector2d c = instanceCentre(inst).head<2>();
        insert(key, {c, c, false});
        break;
      }
    }
  }
}

int64_t MapIndex::cellKey(int key, int64_t ix, int64_t iy) const {
  // 8 bits of match key, 28 bits per axis: cells of 4 m cover +-500 km around the origin.
  const int64_t m = (int64_t{1} << 28) - 1;
  return (int64_t(key) << 56) | ((ix & m) << 28) | (iy & m);
}

void MapIndex::insert(int key, const MapTarget& t) {
  const auto idx = static_cast<uint32_t>(targets_.size());
  targets_.push_back(t);
  // every cell of the segment's bounding box (segments are short polyline pieces)
  voxel_grid::forEachCell2d(
      std::min(t.a.x(), t.b.x()), std::min(t.a.y(), t.b.y()), std::max(t.a.x(), t.b.x()),
      std::max(t.a.y(), t.b.y()), cell_,
      [&](int64_t ix, int64_t iy) { cells_[cellKey(key, ix, iy)].push_back(idx); });
}

TargetMatch MapIndex::nearest(int key, const Eigen::Vector2d& p, double radius) const {
  TargetMatch best;
  best.distance = radius;
  voxel_grid::forEachCell2d(p.x() - radius, p.y() - radius, p.x() + radius, p.y() + radius, cell_,
                            [&](int64_t ix, int64_t iy) {
                              const auto it = cells_.find(cellKey(key, ix, iy));
                              if (it == cells_.end()) return;
                              for (uint32_t i : it->second) {
                                const double d = targetDistance(targets_[i], p);
                                if (d <= best.distance) {
                                  best.distance = d;
                                  best.target = &targets_[i];
                                }
                              }
                            });
  return best;
}

}  // namespace mapfuse::localize
