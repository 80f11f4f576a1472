#include "lane_fragments.hpp"

// Boost.Geometry rtree instantiations trigger GCC false positives.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <numeric>

#include "box2d.hpp"
#include "crossing_lines.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/parallel_for.hpp"
#include "mapfuse/core/union_find.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::aggregate {
namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BoxValue = std::pair<Box2, std::size_t>;

constexpr double kMinSpan = 0.5;  // m, shorter centrelines have no reliable direction

// Fraction of a's centreline points within `tol` of b's centreline.
double coveredFraction(const Fragment& a, const Fragment& b, double tol) {
  if (a.centreline.empty()) return 0.0;
  int inside = 0;
  for (const auto& p : a.centreline)
    if (distanceToPolyline2d(p, b.centreline) <= tol) ++inside;
  return double(inside) / double(a.centreline.size());
}

// Whether two fragments run within `max_angle` (rad, undirected) of each other where they meet:
// crossing lines are not one line (crossing_lines.hpp). Local directions, the shorter
// centreline's against the other's where they come within `near` (a principal axis of a whole
// curved fragment differed from the other's local direction by 30-40 deg on the Karlsruhe
// curves). Fragments too short for a direction agree with any.
bool sameDirection(const Fragment& a, const Fragment& b, double max_angle, double near) {
  const double la = polylineLength(a.centreline), lb = polylineLength(b.centreline);
  if (la < kMinSpan || lb < kMinSpan) return true;
  auto xy = [](const std::vector<Eigen::Vector3d>& c) {
    std::vector<Eigen::Vector2d> out;
    for (const auto& p : c) out.push_back(p.head<2>());
    return out;
  };
  const Fragment& s = la <= lb ? a : b;
  const Fragment& l = la <= lb ? b : a;
  return !piecesCross(xy(s.centreline), xy(l.centreline), near, max_angle);
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
  parallelFor(out.size(), [&](std::size_t k) {  // fragments are independent
    out[k].centreline = binnedCentreline(out[k].samples, station_step);
  });
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
  // Fragments too short for a direction are left to absorbStubs, which gives each to one
  // fragment: here, agreeing with any, they chained two crossing lines into one.
  std::vector<char> directed(frags.size());
  for (std::size_t i = 0; i < frags.size(); ++i)
    directed[i] = polylineLength(frags[i].centreline) >= kMinSpan;
  bool merged = false;
  for (std::size_t i = 0; i < frags.size(); ++i) {
    if (!directed[i]) continue;
    std::vector<BoxValue> hits;
    tree.query(bgi::intersects(boxOf(frags[i].centreline, tol)), std::back_inserter(hits));
    for (const auto& h : hits) {
      const std::size_t j = h.second;
      if (j <= i || !directed[j]) continue;
      if (std::max(coveredFraction(frags[i], frags[j], tol),
                   coveredFraction(frags[j], frags[i], tol)) >= 0.5 &&
          sameDirection(frags[i], frags[j], max_angle, tol)) {
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
      if (h.second == i || stub[h.second] ||
          !sameDirection(frags[i], frags[h.second], max_angle, tol))
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
