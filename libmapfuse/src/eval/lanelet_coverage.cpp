#include "mapfuse/eval/lanelet_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "mapfuse/lanelet/plan.hpp"

namespace mapfuse::eval {

namespace {

constexpr double kCell = 5.0;  // m, grid of line segments and lanelets
using V3 = Eigen::Vector3d;
using Cell = std::pair<int64_t, int64_t>;

Cell cellOf(const V3& p) {
  return {static_cast<int64_t>(std::floor(p.x() / kCell)),
          static_cast<int64_t>(std::floor(p.y() / kCell))};
}

double segmentDistanceXY(const V3& p, const V3& a, const V3& b) {
  const Eigen::Vector2d ab = (b - a).head<2>(), ap = (p - a).head<2>();
  const double len2 = ab.squaredNorm();
  const double u = len2 > 0 ? std::clamp(ap.dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (ap - u * ab).norm();
}

/// Items of a kind on a grid by their bounding boxes.
template <class T>
struct Grid {
  std::map<Cell, std::vector<T>> cells;
  void add(const V3& lo, const V3& hi, const T& item) {
    const Cell a = cellOf(lo), b = cellOf(hi);
    for (int64_t x = a.first; x <= b.first; ++x)
      for (int64_t y = a.second; y <= b.second; ++y) cells[{x, y}].push_back(item);
  }
  const std::vector<T>* at(const V3& p) const {
    const auto it = cells.find(cellOf(p));
    return it == cells.end() ? nullptr : &it->second;
  }
};

}  // namespace

std::vector<LaneletShape> laneletShapes(const io::Lanelet2Map& osm, const geo::GeoOrigin& origin) {
  const geo::EnuConverter enu(origin);
  auto line = [&](int64_t id) {
    std::vector<V3> pts;
    for (const auto& g : osm.way(id)->points) pts.push_back(enu.toEnu(g));
    return pts;
  };
  std::vector<LaneletShape> shapes;
  for (const auto& ll : osm.lanelets) {
    if (ll.subtype == "crosswalk") continue;
    std::vector<V3> left = line(ll.left), right = line(ll.right);
    if ((left.front() - right.front()).norm() + (left.back() - right.back()).norm() >
        (left.front() - right.back()).norm() + (left.back() - right.front()).norm())
      std::reverse(right.begin(), right.end());
    LaneletShape s;
    s.one_way = ll.one_way;
    s.ring = left;
    s.ring.insert(s.ring.end(), right.rbegin(), right.rend());
    const std::size_t n = std::max(left.size(), right.size());
    for (std::size_t k = 0; k < n; ++k) {
      const double f = n > 1 ? double(k) / (n - 1) : 0.0;
      s.centre.push_back(0.5 * (left[std::lround(f * (left.size() - 1))] +
                                right[std::lround(f * (right.size() - 1))]));
    }
    // Travel direction: the left bound lies left of the centre's direction.
    const std::size_t m = s.centre.size() / 2;
    const Eigen::Vector2d d =
        (s.centre[std::min(n - 1, m + 1)] - s.centre[m > 0 ? m - 1 : 0]).head<2>();
    const Eigen::Vector2d l = (left[left.size() / 2] - s.centre[m]).head<2>();
    if (d.x() * l.y() - d.y() * l.x() < 0) std::reverse(s.centre.begin(), s.centre.end());
    shapes.push_back(std::move(s));
  }
  return shapes;
}

LaneletCoverage measureLaneletCoverage(const std::vector<TrueLane>& lanes, const VectorMap& map,
                                       const std::vector<LaneletShape>& lanelets, double step,
                                       double tolerance) {
  Grid<std::pair<std::size_t, std::size_t>> segments;  // (instance, segment)
  for (std::size_t i = 0; i < map.instances.size(); ++i) {
    const auto& m = map.instances[i];
    if (m.cls != CrowdClass::kLaneLine) continue;
    for (std::size_t k = 0; k + 1 < m.points.size(); ++k) {
      const V3 pad(tolerance, tolerance, 0);
      segments.add(m.points[k].cwiseMin(m.points[k + 1]) - pad,
                   m.points[k].cwiseMax(m.points[k + 1]) + pad, {i, k});
    }
  }
  Grid<std::size_t> shapes;
  for (std::size_t l = 0; l < lanelets.size(); ++l) {
    V3 lo = lanelets[l].ring.front(), hi = lo;
    for (const auto& p : lanelets[l].ring) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    shapes.add(lo, hi, l);
  }
  auto nearLine = [&](const V3& p) {
    const auto* cell = segments.at(p);
    if (!cell) return false;
    for (const auto& [i, k] : *cell) {
      const auto& pts = map.instances[i].points;
      if (segmentDistanceXY(p, pts[k], pts[k + 1]) <= tolerance) return true;
    }
    return false;
  };
  LaneletCoverage cov;
  for (const TrueLane& lane : lanes) {
    const auto& c = lane.centre;
    double carried = 0.0;  // arc length since the last sample
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
      const V3 seg = c[k + 1] - c[k];
      const double len = seg.head<2>().norm();
      if (len < 1e-9) continue;
      const Eigen::Vector2d t = seg.head<2>() / len;
      const V3 n(-t.y(), t.x(), 0.0);
      double s = step - carried;
      carried += len;
      for (; s <= len; s += step) {
        carried = len - s;
        const V3 p = c[k] + seg * (s / len);
        const double w = step;
        cov.lane_m += w;
        if (!nearLine(p + 0.5 * lane.width * n) || !nearLine(p - 0.5 * lane.width * n)) continue;
        cov.marked_m += w;
        bool inside = false, with = false, against = false;
        if (const auto* cell = shapes.at(p))
          for (std::size_t l : *cell) {
            const LaneletShape& sh = lanelets[l];
            if (!lanelet::insideRingXY(sh.ring, p)) continue;
            inside = true;
            if (!sh.one_way) continue;
            std::size_t best = 0;
            for (std::size_t q = 1; q + 1 < sh.centre.size(); ++q)
              if ((sh.centre[q] - p).head<2>().norm() < (sh.centre[best] - p).head<2>().norm())
                best = q;
            best = std::min(best, sh.centre.size() - 2);
            const Eigen::Vector2d d = (sh.centre[best + 1] - sh.centre[best]).head<2>();
            (d.dot(t) > 0 ? with : against) = true;
          }
        if (inside) cov.covered_m += w;
        if (with) cov.directed_m += w;
        if (against && !with) cov.reversed_m += w;
      }
    }
  }
  return cov;
}

}  // namespace mapfuse::eval
