#include "polygon_overlap.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace mapfuse::aggregate {
namespace {

using V2 = Eigen::Vector2d;

constexpr double kTol = 1e-9;  // m, closer than this counts as touching (degenerate)

double cross(const V2& a, const V2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

struct Crossing {
  int32_t edge_a, edge_b;  ///< the crossing edges of a and b
  double t_a, t_b;         ///< parameters along the two edges, in (0, 1)
  V2 point;
};

enum class Hit { kNone, kProper, kDegenerate };

// Squared distance from p to the segment [a, b].
double distance2(const V2& p, const V2& a, const V2& b) {
  const V2 d = b - a;
  const double dd = d.squaredNorm();
  const double s = dd > 0 ? std::clamp((p - a).dot(d) / dd, 0.0, 1.0) : 0.0;
  return (a + s * d - p).squaredNorm();
}

// Edges [p0, p1] and [q0, q1]: a proper crossing at p0 + t (p1 - p0) = q0 + u (q1 - q0), none,
// or degenerate (an end point within kTol of the other edge, up to rounding).
Hit edgeCrossing(const V2& p0, const V2& p1, const V2& q0, const V2& q1, double& t, double& u) {
  const V2 d = p1 - p0, e = q1 - q0;
  // orientation of each end point against the other edge's line (signed distance x length)
  const double sq0 = cross(d, q0 - p0), sq1 = cross(d, q1 - p0);
  const double sp0 = cross(e, p0 - q0), sp1 = cross(e, p1 - q0);
  const double band_d = kTol * kTol * d.squaredNorm(), band_e = kTol * kTol * e.squaredNorm();
  if (sq0 * sq0 > band_d && sq1 * sq1 > band_d && sp0 * sp0 > band_e && sp1 * sp1 > band_e) {
    // every end point is farther than kTol from the other line: the signs are exact, and a
    // crossing lies farther than kTol from every end point
    if ((sq0 > 0) == (sq1 > 0) || (sp0 > 0) == (sp1 > 0)) return Hit::kNone;
    t = sp0 / (sp0 - sp1);
    u = sq0 / (sq0 - sq1);
    return Hit::kProper;
  }
  // an end point lies near the other line: had the edges crossed or touched, some end point
  // would lie within kTol of the other edge itself (2 kTol covers the rounding)
  const double lim = 4 * kTol * kTol;
  if (distance2(q0, p0, p1) <= lim || distance2(q1, p0, p1) <= lim ||
      distance2(p0, q0, q1) <= lim || distance2(p1, q0, q1) <= lim)
    return Hit::kDegenerate;
  return Hit::kNone;
}

// Crossing number of the ray from pt towards +x with the edges of a polygon set; pt is farther
// than kTol from every edge, so the orientation sign decides the edges pt is level with.
bool inside(const V2& pt, const std::vector<V2>& vertices, const std::vector<int32_t>& next) {
  bool in = false;
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const V2& u = vertices[k];
    const V2& v = vertices[std::size_t(next[k])];
    if ((u.y() > pt.y()) == (v.y() > pt.y())) continue;
    const double lo = std::min(u.x(), v.x()), hi = std::max(u.x(), v.x());
    const bool right =
        pt.x() < lo || (pt.x() <= hi && (cross(v - u, pt - u) > 0) == (v.y() > u.y()));
    if (right) in = !in;
  }
  return in;
}

}  // namespace

OverlapPolygon::OverlapPolygon(const std::vector<std::vector<V2>>& rings, const V2& origin)
    : origin_(origin) {
  double signed_area = 0.0;
  for (const auto& ring : rings) {
    std::vector<V2> r;
    r.reserve(ring.size());
    for (const auto& p : ring) {
      const V2 q = p - origin;
      if (r.empty() || q != r.back()) r.push_back(q);
    }
    while (r.size() > 1 && r.back() == r.front()) r.pop_back();
    if (r.size() < 3) continue;
    ring_start_.push_back(int32_t(vertices_.size()));
    for (std::size_t i = 0; i < r.size(); ++i) {
      signed_area += 0.5 * cross(r[i], r[(i + 1) % r.size()]);
      vertices_.push_back(r[i]);
    }
  }
  if (vertices_.empty()) return;
  ring_start_.push_back(int32_t(vertices_.size()));
  if (signed_area < 0) {  // clockwise outer rings: reverse every ring, region to the left
    for (std::size_t r = 0; r + 1 < ring_start_.size(); ++r)
      std::reverse(vertices_.begin() + ring_start_[r], vertices_.begin() + ring_start_[r + 1]);
  }
  area_ = std::abs(signed_area);
  const std::size_t n = vertices_.size();
  next_.resize(n);
  for (std::size_t r = 0; r + 1 < ring_start_.size(); ++r)
    for (int32_t k = ring_start_[r]; k < ring_start_[r + 1]; ++k)
      next_[std::size_t(k)] = k + 1 < ring_start_[r + 1] ? k + 1 : ring_start_[r];
  edge_lo_.resize(n);
  edge_hi_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    edge_lo_[k] = vertices_[k].cwiseMin(vertices_[std::size_t(next_[k])]);
    edge_hi_[k] = vertices_[k].cwiseMax(vertices_[std::size_t(next_[k])]);
  }
  lo_ = hi_ = vertices_[0];
  for (const auto& v : vertices_) lo_ = lo_.cwiseMin(v), hi_ = hi_.cwiseMax(v);
  for (int axis = 0; axis < 2; ++axis) {
    auto& order = order_[axis];
    order.resize(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int32_t i, int32_t j) {
      const double ki = edge_lo_[std::size_t(i)][axis], kj = edge_lo_[std::size_t(j)][axis];
      return ki < kj || (ki == kj && i < j);
    });
  }
}

std::vector<std::vector<V2>> OverlapPolygon::localRings() const {
  std::vector<std::vector<V2>> out;
  for (std::size_t r = 0; r + 1 < ring_start_.size(); ++r)
    out.emplace_back(vertices_.begin() + ring_start_[r], vertices_.begin() + ring_start_[r + 1]);
  return out;
}

std::optional<double> intersectionArea(const OverlapPolygon& a, const OverlapPolygon& b) {
  if (a.origin_ != b.origin_)
    throw std::invalid_argument("intersectionArea: the two polygons have different origins");
  if (a.empty() || b.empty()) return 0.0;
  const V2 olo = a.lo_.cwiseMax(b.lo_), ohi = a.hi_.cwiseMin(b.hi_);
  if (olo.x() > ohi.x() + kTol || olo.y() > ohi.y() + kTol) return 0.0;
  if (a.ring_start_ == b.ring_start_ && a.vertices_ == b.vertices_) return a.area_;

  // ---- all proper crossings of an edge of a with an edge of b: sort and sweep along `axis`
  const int axis = ohi.x() - olo.x() >= ohi.y() - olo.y() ? 0 : 1, other = 1 - axis;
  // an edge outside the overlap box (by more than kTol) cannot meet the other polygon
  auto relevant = [&](const OverlapPolygon& p, int32_t k) {
    const V2& lo = p.edge_lo_[std::size_t(k)];
    const V2& hi = p.edge_hi_[std::size_t(k)];
    return hi[axis] >= olo[axis] - kTol && lo[other] <= ohi[other] + kTol &&
           hi[other] >= olo[other] - kTol;
  };
  thread_local std::vector<Crossing> crossings;
  thread_local std::vector<int32_t> active[2];  // edges of a (0) and b (1) the sweep has reached
  crossings.clear();
  active[0].clear();
  active[1].clear();
  const OverlapPolygon* poly[2] = {&a, &b};
  std::size_t pos[2] = {0, 0};
  const std::size_t size[2] = {a.order_[axis].size(), b.order_[axis].size()};
  const double stop = ohi[axis] + kTol;
  while (pos[0] < size[0] || pos[1] < size[1]) {
    // next edge by lower coordinate along the axis, from either polygon
    const int side = pos[1] >= size[1] ? 0
                     : pos[0] >= size[0]
                         ? 1
                         : (a.edge_lo_[std::size_t(a.order_[axis][pos[0]])][axis] <=
                                    b.edge_lo_[std::size_t(b.order_[axis][pos[1]])][axis]
                                ? 0
                                : 1);
    const OverlapPolygon& p = *poly[side];
    const OverlapPolygon& q = *poly[1 - side];
    const int32_t k = p.order_[axis][pos[side]++];
    const V2& klo = p.edge_lo_[std::size_t(k)];
    const V2& khi = p.edge_hi_[std::size_t(k)];
    if (klo[axis] > stop) break;  // and so are all later edges
    if (!relevant(p, k)) continue;
    auto& others = active[1 - side];
    std::size_t kept = 0;
    for (const int32_t j : others) {
      const V2& jlo = q.edge_lo_[std::size_t(j)];
      const V2& jhi = q.edge_hi_[std::size_t(j)];
      if (jhi[axis] < klo[axis] - kTol) continue;  // behind the sweep for good: drop
      others[kept++] = j;
      if (jlo[other] > khi[other] + kTol || jhi[other] < klo[other] - kTol) continue;
      const int32_t ea = side == 0 ? k : j, eb = side == 0 ? j : k;
      const V2& p0 = a.vertices_[std::size_t(ea)];
      const V2& p1 = a.vertices_[std::size_t(a.next_[ea])];
      double t = 0, u = 0;
      const Hit hit = edgeCrossing(p0, p1, b.vertices_[std::size_t(eb)],
                                   b.vertices_[std::size_t(b.next_[eb])], t, u);
      if (hit == Hit::kDegenerate) return std::nullopt;
      if (hit == Hit::kProper) crossings.push_back({ea, eb, t, u, p0 + t * (p1 - p0)});
    }
    others.resize(kept);
    active[side].push_back(k);
  }

  // ---- boundary pieces of p inside q, walked ring by ring; the state toggles at crossings
  double twice = 0.0;
  for (int side = 0; side < 2; ++side) {
    const OverlapPolygon& p = *poly[side];
    const OverlapPolygon& q = *poly[1 - side];
    auto edge = [side](const Crossing& x) { return side == 0 ? x.edge_a : x.edge_b; };
    auto param = [side](const Crossing& x) { return side == 0 ? x.t_a : x.t_b; };
    std::sort(crossings.begin(), crossings.end(), [&](const Crossing& x, const Crossing& y) {
      return edge(x) < edge(y) || (edge(x) == edge(y) && param(x) < param(y));
    });
    std::size_t c = 0;
    for (std::size_t r = 0; r + 1 < p.ring_start_.size(); ++r) {
      const int32_t first = p.ring_start_[r], end = p.ring_start_[r + 1];
      const V2& start = p.vertices_[std::size_t(first)];
      const bool in_box =
          (start.array() >= q.lo_.array()).all() && (start.array() <= q.hi_.array()).all();
      bool in = in_box && inside(start, q.vertices_, q.next_);
      for (int32_t k = first; k < end; ++k) {
        V2 cur = p.vertices_[std::size_t(k)];
        for (; c < crossings.size() && edge(crossings[c]) == k; ++c) {
          if (in) twice += cross(cur, crossings[c].point);
          cur = crossings[c].point;
          in = !in;
        }
        if (in) twice += cross(cur, p.vertices_[std::size_t(p.next_[k])]);
      }
    }
  }
  // rounding only: the exact value lies in [0, smaller area]
  return std::clamp(0.5 * twice, 0.0, std::min(a.area_, b.area_));
}

}  // namespace mapfuse::aggregate
