#include "lane_fragments.hpp"

// Boost.Geometry rtree instantiations trigger GCC false positives.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <numeric>

#include "box2d.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/union_find.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::aggregate {
namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BoxValue = std::pair<Box2, std::size_t>;

// Fraction of a's centreline points within `tol` of b's centreline.
double coveredFraction(const Fragment& a, const Fragment& b, double tol) {
  if (a.centreline.empty()) return 0.0;
  int inside = 0;
  for (const auto& p : a.centreline)
    if (distanceToPolyline2d(p, b.centreline) <= tol) ++inside;
  return double(inside) / double(a.centreline.size());
}

// Whether two fragments run within `max_angle` (rad, undirected) of each other where they meet:
// crossing lines are not one line (crossing_lines.hpp). The shorter one's principal axis against
// the other's centreline segment nearest to its centre (a long fragment may curve). Fragments too
// short for a direction agree with any.
bool sameDirection(const Fragment& a, const Fragment& b, double max_angle) {
  constexpr double kMinSpan = 0.5;  // m, shorter centrelines have no reliable direction
  const double la = polylineLength(a.centreline), lb = polylineLength(b.centreline);
  if (la < kMinSpan || lb < kMinSpan) return true;
  const Fragment& s = la <= lb ? a : b;
  const Fragment& l = la <= lb ? b : a;
  const Eigen::Vector2d ds = principalAxis2d(s.samples.empty() ? s.centreline : s.samples);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : s.centreline) c += p;
  c /= double(s.centreline.size());
  double best = 1e300;
  Eigen::Vector2d dl = ds;
  for (std::size_t k = 1; k < l.centreline.size(); ++k) {
    const Eigen::Vector2d d = (l.centreline[k] - l.centreline[k - 1]).head<2>();
    if (d.norm() < 1e-9) continue;
    const double dist = distanceToSegment2d(c, l.centreline[k - 1], l.centreline[k]);
    if (dist < best) best = dist, dl = d.normalized();
  }
  return std::abs(ds.dot(dl)) >= std::cos(max_angle);
}

// Pools fragments into the union-find roots of `parent`; centrelines recomputed.
void poolFragments(std::vector<Fragment>& frags, std::vector<int>& parent, double station_step) {
  std::vector<Fragment> out;
  std::vector<int> slot(frags.size(), -1);
  for (std::size_t i = 0; i < frags.size(); ++i) {
    const int r = findRoot(parent, int(i));
    if (slot[r] < 0) {
      slot[r] = int(out.size());
      out.emplace_back();
    }
    Fragment& f = out[std::size_t(slot[r])];
    f.samples.insert(f.samples.end(), frags[i].samples.begin(), frags[i].samples.end());
    f.obs.insert(frags[i].obs.begin(), frags[i].obs.end());
  }
  for (auto& f : out) f.centreline = binnedCentreline(f.samples, station_step);
  frags = std::move(out);
}

bgi::rtree<BoxValue, bgi::rstar<16>> fragmentBoxes(const std::vector<Fragment>& frags,
                                                   double margin) {
  std::vector<BoxValue> fb;
  for (std::size_t i = 0; i < frags.size(); ++i)
    fb.push_back({boxOf(frags[i].centreline, margin), i});
  return bgi::rtree<BoxValue, bgi::rstar<16>>(fb.begin(), fb.end());
}

}  // namespace

void mergeSideBySide(std::vector<Fragment>& frags, const LaneInstantiationParams& p) {
  const double tol = 2 * p.buffer_width;
  const double max_angle = p.piece_angle_deg * M_PI / 180.0;
  const auto tree = fragmentBoxes(frags, tol);
  std::vector<int> parent(frags.size());
  std::iota(parent.begin(), parent.end(), 0);
  bool merged = false;
  for (std::size_t i = 0; i < frags.size(); ++i) {
    std::vector<BoxValue> hits;
    tree.query(bgi::intersects(boxOf(frags[i].centreline, tol)), std::back_inserter(hits));
    for (const auto& h : hits) {
      const std::size_t j = h.second;
      if (j <= i) continue;
      if (std::max(coveredFraction(frags[i], frags[j], tol),
                   coveredFraction(frags[j], frags[i], tol)) >= 0.5 &&
          sameDirection(frags[i], frags[j], max_angle)) {
        parent[findRoot(parent, int(j))] = findRoot(parent, int(i));
        merged = true;
      }
    }
  }
  if (merged) poolFragments(frags, parent, p.station_step);
}

void absorbStubs(std::vector<Fragment>& frags, const LaneInstantiationParams& p) {
  const double tol = p.station_step;
  const double max_angle = p.piece_angle_deg * M_PI / 180.0;
  std::vector<char> stub(frags.size());
  for (std::size_t i = 0; i < frags.size(); ++i)
    stub[i] = polylineLength(frags[i].centreline) < tol;
  const auto tree = fragmentBoxes(frags, tol);
  std::vector<int> parent(frags.size());
  std::iota(parent.begin(), parent.end(), 0);
  bool merged = false;
  for (std::size_t i = 0; i < frags.size(); ++i) {
    if (!stub[i]) continue;
    std::vector<BoxValue> hits;
    tree.query(bgi::intersects(boxOf(frags[i].centreline, tol)), std::back_inserter(hits));
    double best = tol;
    int target = -1;
    for (const auto& h : hits) {
      if (h.second == i || stub[h.second] || !sameDirection(frags[i], frags[h.second], max_angle))
        continue;
      for (const auto& q : frags[i].centreline) {
        const double d = distanceToPolyline2d(q, frags[h.second].centreline);
        if (d <= best) best = d, target = int(h.second);
      }
    }
    if (target >= 0) {
      parent[i] = target;  // targets are no stubs, so they stay roots
      merged = true;
    }
  }
  if (merged) poolFragments(frags, parent, p.station_step);
}

}  // namespace mapfuse::aggregate
