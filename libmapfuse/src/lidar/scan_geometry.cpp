#include "mapfuse/lidar/scan_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/param_check.hpp"

namespace mapfuse::lidar {
namespace {

/// Lowest z per ground cell, then the lower envelope of cones of slope `slope` standing on the
/// neighbours' lowest returns: ground(c) = min over |dx|, |dy| <= w of low(c + d) + slope (|dx| +
/// |dy|) cell (two separable passes). Terrain rising less steeply than the slope stays ground;
/// an object's top is measured from the road beside it.
struct GroundGrid {
  double x0 = 0, y0 = 0, inv = 1;
  int64_t nx = 0, ny = 0;
  std::vector<double> height;
  int64_t cell(const Eigen::Vector3d& p) const {
    const int64_t ix = std::clamp<int64_t>(int64_t((p.x() - x0) * inv), 0, nx - 1);
    const int64_t iy = std::clamp<int64_t>(int64_t((p.y() - y0) * inv), 0, ny - 1);
    return iy * nx + ix;
  }
};

GroundGrid groundGrid(const std::vector<Eigen::Vector3d>& pts, double cell, int w, double slope) {
  GroundGrid g;
  Eigen::Vector3d lo = pts.front(), hi = pts.front();
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  g.x0 = lo.x();
  g.y0 = lo.y();
  g.inv = 1.0 / cell;
  g.nx = int64_t((hi.x() - lo.x()) * g.inv) + 1;
  g.ny = int64_t((hi.y() - lo.y()) * g.inv) + 1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> low(std::size_t(g.nx * g.ny), kInf), tmp(low.size(), kInf);
  for (const auto& p : pts) {
    double& v = low[std::size_t(g.cell(p))];
    v = std::min(v, p.z());
  }
  const double rise = slope * cell;  // per cell step
  for (int64_t y = 0; y < g.ny; ++y)
    for (int64_t x = 0; x < g.nx; ++x) {
      double m = kInf;
      for (int64_t k = std::max<int64_t>(0, x - w); k <= std::min<int64_t>(g.nx - 1, x + w); ++k)
        m = std::min(m, low[std::size_t(y * g.nx + k)] + rise * double(std::abs(k - x)));
      tmp[std::size_t(y * g.nx + x)] = m;
    }
  g.height.assign(low.size(), kInf);
  for (int64_t y = 0; y < g.ny; ++y)
    for (int64_t x = 0; x < g.nx; ++x) {
      double m = kInf;
      for (int64_t k = std::max<int64_t>(0, y - w); k <= std::min<int64_t>(g.ny - 1, y + w); ++k)
        m = std::min(m, tmp[std::size_t(k * g.nx + x)] + rise * double(std::abs(k - y)));
      g.height[std::size_t(y * g.nx + x)] = m;
    }
  return g;
}

}  // namespace

std::vector<ScanPointKind> splitScanGeometry(const std::vector<Eigen::Vector3d>& pts,
                                             const SceneGeometrySettings& s,
                                             SceneGeometryStats* stats,
                                             std::vector<double>* heights) {
  param::validate(s);
  std::vector<ScanPointKind> kind(pts.size(), ScanPointKind::kStatic);
  SceneGeometryStats st;
  if (pts.empty()) {
    if (stats) *stats = st;
    return kind;
  }
  const GroundGrid g = groundGrid(pts, s.ground_cell, s.ground_window, s.ground_slope);
  if (heights) heights->assign(pts.size(), 0.0);
  // Non-ground points keyed by column, then ordered by height above the ground.
  struct Entry {
    uint64_t column;
    double h;
    uint32_t index;
    bool operator<(const Entry& o) const {
      return column != o.column ? column < o.column : h < o.h;
    }
  };
  std::vector<Entry> entries;
  entries.reserve(pts.size());
  const double inv = 1.0 / s.column_cell;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double h = pts[i].z() - g.height[std::size_t(g.cell(pts[i]))];
    if (heights) (*heights)[i] = h;
    if (h <= s.ground_tolerance) {
      kind[i] = ScanPointKind::kGround;
      continue;
    }
    const uint64_t cx = uint64_t(int64_t(std::floor((pts[i].x() - g.x0) * inv)));
    const uint64_t cy = uint64_t(int64_t(std::floor((pts[i].y() - g.y0) * inv)));
    entries.push_back({cx << 32 | cy, h, uint32_t(i)});
  }
  std::sort(entries.begin(), entries.end());
  // Segments: runs of one column without a vertical gap wider than max_gap.
  for (std::size_t a = 0; a < entries.size();) {
    std::size_t b = a + 1;
    while (b < entries.size() && entries[b].column == entries[a].column &&
           entries[b].h - entries[b - 1].h <= s.max_gap)
      ++b;
    const bool road_user = entries[a].h <= s.max_bottom && entries[b - 1].h <= s.max_height;
    ++st.segments;
    st.road_user_segments += road_user;
    if (road_user)
      for (std::size_t k = a; k < b; ++k) kind[entries[k].index] = ScanPointKind::kRoadUser;
    a = b;
  }
  for (ScanPointKind k : kind) {
    st.ground += k == ScanPointKind::kGround;
    st.static_points += k == ScanPointKind::kStatic;
    st.road_user += k == ScanPointKind::kRoadUser;
  }
  if (stats) *stats = st;
  return kind;
}

}  // namespace mapfuse::lidar
