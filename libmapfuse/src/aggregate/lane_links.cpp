#include "lane_links.hpp"

// Boost.Geometry rtree instantiations trigger GCC false positives.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <set>

#include "arc_link.hpp"
#include "box2d.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::aggregate {
namespace {

namespace bgi = boost::geometry::index;
using PointValue = std::pair<P2, std::size_t>;

constexpr double kArcTail = 4.0;  // m of a fragment's end the arc link test fits

}  // namespace

struct FragmentEnds::Index {
  explicit Index(const std::vector<PointValue>& points) : tree(points.begin(), points.end()) {}
  bgi::rtree<PointValue, bgi::rstar<16>> tree;
};

FragmentEnds::FragmentEnds(const std::vector<Fragment>& frags, const LaneInstantiationParams& p)
    : p_(p), cos_max_(std::cos(p.link_angle_deg * M_PI / 180.0)) {
  const std::size_t m = frags.size();
  ends_.resize(2 * m);
  std::vector<PointValue> end_points(2 * m);
  for (std::size_t f = 0; f < m; ++f) {
    const auto& c = frags[f].centreline;
    for (int w = 0; w < 2; ++w) {
      Eigen::Vector2d axis = principalAxis2d(c);
      if (c.size() >= 2 && (c.back() - c.front()).head<2>().dot(axis) < 0) axis = -axis;
      ends_[2 * f + w] = w == 0 ? End{c.front(), -axis} : End{c.back(), axis};
      end_points[2 * f + w] = {P2(ends_[2 * f + w].pos.x(), ends_[2 * f + w].pos.y()), 2 * f + w};
    }
  }
  index_ = std::make_unique<Index>(end_points);
  from_end_.resize(2 * m);
  to_end_.resize(2 * m);
  for (std::size_t e = 0; e < 2 * m; ++e) {
    const auto& c = frags[e / 2].centreline;
    auto& t = from_end_[e];
    double run = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      const std::size_t i = e % 2 == 0 ? k : c.size() - 1 - k;
      if (k > 0) run += (c[i] - t.back()).head<2>().norm();
      if (run > kArcTail) break;
      t.push_back(c[i]);
    }
    to_end_[e].assign(t.rbegin(), t.rend());
  }
}

FragmentEnds::~FragmentEnds() = default;

// b lies ahead of a, facing back at it
bool FragmentEnds::follows(const End& a, const End& b) const {
  if (a.dir.dot(b.dir) > -cos_max_) return false;
  const Eigen::Vector2d v = (b.pos - a.pos).head<2>();
  const double along = v.dot(a.dir);
  const double lateral = (v - along * a.dir).norm();
  return along >= -p_.link_lateral && along <= p_.link_distance && lateral <= p_.link_lateral;
}

bool FragmentEnds::straight(std::size_t e, std::size_t f) const {
  return follows(ends_[e], ends_[f]) && follows(ends_[f], ends_[e]);
}

// both ends' last kArcTail metres on one circle (radius >= 4 m, residual <= 0.15 m), the gap
// along it within link_distance
bool FragmentEnds::onArc(std::size_t e, std::size_t f) const {
  ArcLinkLimits arc;
  arc.max_gap = p_.link_distance;
  return (ends_[f].pos - ends_[e].pos).head<2>().norm() <= p_.link_distance &&
         continuesOnArc(to_end_[e], from_end_[f], arc);
}

// |N_eps| of an end counts the fragments that follow it directly. A candidate lying beyond
// the far end of a nearer candidate (plus a station) follows that one, not this end: short
// fragments of one dashed line all lie within the link distance, and counting them as a
// fork left the dashes unlinked. Branches of a real fork start side by side and survive.
void FragmentEnds::dropShadowed(std::size_t e, std::vector<std::size_t>& cand) const {
  if (cand.size() < 2) return;
  const double slack = p_.station_step;
  auto along = [&](std::size_t f) {
    return (ends_[f].pos - ends_[e].pos).head<2>().dot(ends_[e].dir);
  };
  std::vector<std::size_t> kept;
  for (std::size_t f : cand) {
    bool shadowed = false;
    for (std::size_t g : cand)
      if (g != f && along(g ^ 1) <= along(f) + slack && along(g) < along(f)) shadowed = true;
    if (!shadowed) kept.push_back(f);
  }
  cand = std::move(kept);
}

std::vector<std::size_t> FragmentEnds::candidates(std::size_t e) const {
  const double reach = std::max(p_.link_distance, p_.link_lateral);
  const auto& q = ends_[e].pos;
  const Box2 box(P2(q.x() - reach, q.y() - reach), P2(q.x() + reach, q.y() + reach));
  std::vector<PointValue> hits;
  index_->tree.query(bgi::within(box), std::back_inserter(hits));
  std::vector<std::size_t> cand;
  for (const auto& h : hits) {
    const std::size_t f = h.second;
    if (f / 2 == e / 2) continue;
    if (straight(e, f) || (onArc(e, f) && onArc(f, e))) cand.push_back(f);
  }
  dropShadowed(e, cand);
  std::sort(cand.begin(), cand.end());
  return cand;
}

std::vector<Eigen::Vector3d> FragmentEnds::bridge(std::size_t from, std::size_t to) const {
  if (straight(from, to)) return {};
  return arcBridge(to_end_[from], from_end_[to], p_.station_step);
}

std::vector<long> linkEnds(const std::vector<std::vector<std::size_t>>& cand,
                           const LaneInstantiationParams& p, LaneInstantiationStats& stats) {
  auto isCore = [&](std::size_t e) {
    const int size = 1 + int(cand[e].size());  // |N_eps| counts the end itself
    return p.link_min_pts <= size && size <= p.link_max_pts;
  };
  std::vector<long> link(cand.size(), -1);
  for (std::size_t e = 0; e < cand.size(); ++e) {
    if (1 + int(cand[e].size()) > p.link_max_pts) ++stats.branch_ends;
    if (!isCore(e)) continue;
    for (std::size_t f : cand[e])
      if (isCore(f) && link[f] < 0 && link[e] < 0) {
        link[e] = long(f);
        link[f] = long(e);
        ++stats.links;
      }
  }
  return link;
}

namespace {

// The chain of linked fragments from fragment `start`, entered at its end `entry`; marks the
// fragments it passes as used.
LaneInstance walkChain(const std::vector<Fragment>& frags, const FragmentEnds& ends,
                       const std::vector<long>& link, std::size_t start, int entry,
                       std::vector<bool>& used) {
  LaneInstance inst;
  std::set<std::size_t> obs;
  std::size_t f = start;
  int in = entry;
  long from = -1;  // the end of the previous fragment linked to this one
  while (!used[f]) {
    used[f] = true;
    ++inst.fragments;
    auto c = frags[f].centreline;
    if (in == 1) std::reverse(c.begin(), c.end());
    if (from >= 0) {  // follow the arc, no chord
      const auto bridge = ends.bridge(std::size_t(from), 2 * f + in);
      inst.centreline.insert(inst.centreline.end(), bridge.begin(), bridge.end());
    }
    inst.centreline.insert(inst.centreline.end(), c.begin(), c.end());
    obs.insert(frags[f].obs.begin(), frags[f].obs.end());
    from = long(2 * f + (1 - in));
    const long next = link[std::size_t(from)];
    if (next < 0) break;
    f = std::size_t(next) / 2;
    in = int(next % 2);
  }
  inst.observations.assign(obs.begin(), obs.end());
  return inst;
}

}  // namespace

std::vector<LaneInstance> chainFragments(const std::vector<Fragment>& frags,
                                         const FragmentEnds& ends, const std::vector<long>& link,
                                         const LaneInstantiationParams& p,
                                         LaneInstantiationStats& stats) {
  const std::size_t m = frags.size();
  std::vector<bool> used(m, false);
  std::vector<LaneInstance> instances;
  auto keep = [&](LaneInstance inst) {
    if (polylineLength(inst.centreline) < p.min_instance_length)
      ++stats.dropped_short;
    else
      instances.push_back(std::move(inst));
  };
  for (std::size_t f = 0; f < m; ++f)
    if (!used[f] && (link[2 * f] < 0 || link[2 * f + 1] < 0))
      keep(walkChain(frags, ends, link, f, link[2 * f] < 0 ? 0 : 1, used));
  for (std::size_t f = 0; f < m; ++f)  // closed loops
    if (!used[f]) keep(walkChain(frags, ends, link, f, 0, used));
  return instances;
}

}  // namespace mapfuse::aggregate
