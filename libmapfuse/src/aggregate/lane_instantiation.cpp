#include "mapfuse/aggregate/lane_instantiation.hpp"

// Boost.Geometry buffer/rtree instantiations trigger GCC false positives.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <numeric>
#include <optional>
#include <set>

#include "box2d.hpp"
#include "lane_fragments.hpp"
#include "mapfuse/aggregate/arc_link.hpp"
#include "mapfuse/aggregate/dbscan.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/aggregate/line_buffer.hpp"
#include "mapfuse/aggregate/polygon_overlap.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "partner_drives.hpp"

namespace mapfuse::aggregate {
using detail::partnerDrives;
namespace {

constexpr double kSimplifyTolerance = 0.02;  // m
constexpr double kArcTail = 4.0;             // m of a fragment's end the arc link test fits

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using Vec3 = Eigen::Vector3d;
using Line2 = bg::model::linestring<P2>;
using Poly2 = bg::model::polygon<P2>;
using MPoly2 = bg::model::multi_polygon<Poly2>;
using PointValue = std::pair<P2, std::size_t>;

struct Piece {
  std::size_t obs = 0;  ///< index into items
  int64_t tile = 0;
  Eigen::Vector2d corner{0, 0};  ///< lower-left corner of the tile (local origin of stage 1)
  std::vector<Vec3> points;
};

int64_t tileKey(const Vec3& p, double size) {
  const int64_t ix = int64_t(std::floor(p.x() / size));
  const int64_t iy = int64_t(std::floor(p.y() / size));
  return (ix << 32) ^ (iy & 0xffffffffLL);
}

// Cuts a polyline where it crosses the tile grid; each piece lies in one tile.
void cutAtTiles(const std::vector<Vec3>& pts, double size, std::size_t obs,
                std::vector<Piece>& out) {
  Piece cur;
  bool open = false;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const Vec3 a = pts[i - 1], d = pts[i] - a;
    if (d.head<2>().norm() < 1e-6) continue;
    std::vector<double> ts{0.0, 1.0};
    for (int axis = 0; axis < 2; ++axis) {
      if (std::abs(d[axis]) < 1e-12) continue;
      const double lo = std::min(a[axis], a[axis] + d[axis]);
      const double hi = std::max(a[axis], a[axis] + d[axis]);
      for (double g = std::ceil(lo / size) * size; g < hi; g += size) {
        const double t = (g - a[axis]) / d[axis];
        if (t > 1e-9 && t < 1 - 1e-9) ts.push_back(t);
      }
    }
    std::sort(ts.begin(), ts.end());
    for (std::size_t k = 1; k < ts.size(); ++k) {
      const Vec3 p = a + ts[k - 1] * d, q = a + ts[k] * d;
      const Vec3 mid = 0.5 * (p + q);
      const int64_t key = tileKey(mid, size);
      if (!open || key != cur.tile) {
        if (open) out.push_back(std::move(cur));
        const Eigen::Vector2d corner(std::floor(mid.x() / size) * size,
                                     std::floor(mid.y() / size) * size);
        cur = Piece{obs, key, corner, {p}};
        open = true;
      }
      cur.points.push_back(q);
    }
  }
  if (open) out.push_back(std::move(cur));
}

Line2 toLine(const std::vector<Vec3>& pts) {
  Line2 l;
  for (const auto& p : pts)
    if (l.empty() || std::hypot(p.x() - bg::get<0>(l.back()), p.y() - bg::get<1>(l.back())) > 1e-3)
      l.emplace_back(p.x(), p.y());
  return l;
}

// The stage-1 polygon of a piece: simplified first (Douglas-Peucker, 2 cm: fewer polygon
// vertices, same overlap areas), then buffered by +-width with flat ends and mitre joins.
MPoly2 bufferPiece(const Piece& piece, double width) {
  const bg::strategy::buffer::distance_symmetric<double> distance(width);
  const bg::strategy::buffer::side_straight side;
  const bg::strategy::buffer::join_miter join;
  const bg::strategy::buffer::end_flat end;
  const bg::strategy::buffer::point_circle circle(8);
  Line2 simple;
  bg::simplify(toLine(piece.points), simple, kSimplifyTolerance);
  MPoly2 out;
  bg::buffer(simple, out, distance, side, join, end, circle);
  return out;
}

OverlapPolygon toOverlapPolygon(const MPoly2& mp, const Eigen::Vector2d& origin) {
  std::vector<std::vector<Eigen::Vector2d>> rings;
  auto add = [&](const auto& ring) {
    rings.emplace_back();
    for (const auto& q : ring) rings.back().emplace_back(bg::get<0>(q), bg::get<1>(q));
  };
  for (const auto& poly : mp) {
    add(poly.outer());
    for (const auto& inner : poly.inners()) add(inner);
  }
  return OverlapPolygon(rings, origin);
}

struct End {
  Vec3 pos;
  Eigen::Vector2d dir;  ///< outward unit direction
};

End endOf(const Fragment& f, int which) {
  const auto& c = f.centreline;
  Eigen::Vector2d axis = principalAxis2d(c);
  if (c.size() >= 2 && (c.back() - c.front()).head<2>().dot(axis) < 0) axis = -axis;
  return which == 0 ? End{c.front(), -axis} : End{c.back(), axis};
}

// |N_eps| of an end counts the fragments that follow it directly. A candidate lying beyond
// the far end of a nearer candidate (plus `slack`) follows that one, not this end: short
// fragments of one dashed line all lie within the link distance, and counting them as a
// fork left the dashes unlinked. Branches of a real fork start side by side and survive.
void dropShadowed(const std::vector<End>& ends, std::size_t e, double slack,
                  std::vector<std::size_t>& cand) {
  if (cand.size() < 2) return;
  auto along = [&](std::size_t f) {
    return (ends[f].pos - ends[e].pos).head<2>().dot(ends[e].dir);
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
}  // namespace

LaneInstantiation instantiateLanes(const std::vector<Observation>& items,
                                   const std::vector<std::size_t>& indices,
                                   const LaneInstantiationParams& p, int num_drives) {
  LaneInstantiation result;
  // ---- tiling: pieces of observations, each inside one tile
  std::vector<Piece> pieces;
  for (std::size_t idx : indices) cutAtTiles(items[idx].points, p.tile_size, idx, pieces);
  pieces.erase(std::remove_if(pieces.begin(), pieces.end(),
                              [](const Piece& q) { return toLine(q.points).size() < 2; }),
               pieces.end());
  const std::size_t n = pieces.size();
  result.stats.pieces = n;
  if (n == 0) return result;

  // ---- stage 1: buffered polygons, overlap-area similarity, DBSCAN
  // (the polygons in tile-local coordinates, prepared for the exact overlap area)
  std::vector<OverlapPolygon> polys(n);
  std::vector<double> areas(n);
  std::vector<Box2> boxes(n);
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t si = 0; si < std::ptrdiff_t(n); ++si) {
    const std::size_t i = std::size_t(si);
    // The buffer ring built directly (line_buffer.hpp); Boost's where that may differ.
    Line2 simple;
    bg::simplify(toLine(pieces[i].points), simple, kSimplifyTolerance);
    std::vector<Eigen::Vector2d> line;
    for (const auto& q : simple) line.emplace_back(bg::get<0>(q), bg::get<1>(q));
    if (const auto ring = mitreBuffer(line, p.buffer_width)) {
      areas[i] = ringArea(*ring);
      polys[i] = OverlapPolygon({*ring}, pieces[i].corner);
    } else {
      const MPoly2 buffered = bufferPiece(pieces[i], p.buffer_width);
      areas[i] = bg::area(buffered);
      polys[i] = toOverlapPolygon(buffered, pieces[i].corner);
    }
    boxes[i] = boxOf(pieces[i].points, p.buffer_width);
  }
  // Candidates: pieces of the same tile whose boxes intersect (touching counts), of at most
  // `partner_drives` other drives per piece (partner_drives.hpp). Tile by tile: a piece's
  // neighbours all lie in its own tile, so tiles run in parallel without sharing lists.
  std::vector<std::size_t> by_tile(n);
  std::iota(by_tile.begin(), by_tile.end(), std::size_t(0));
  auto driveOf = [&](std::size_t i) { return items[pieces[i].obs].drive; };
  std::stable_sort(by_tile.begin(), by_tile.end(), [&](std::size_t a, std::size_t b) {
    return pieces[a].tile != pieces[b].tile ? pieces[a].tile < pieces[b].tile
                                            : driveOf(a) < driveOf(b);
  });
  std::vector<std::pair<std::size_t, std::size_t>> tiles;  // [begin, end) in by_tile
  for (std::size_t k = 0; k < n;) {
    std::size_t e = k;
    while (e < n && pieces[by_tile[e]].tile == pieces[by_tile[k]].tile) ++e;
    tiles.emplace_back(k, e);
    k = e;
  }
  std::vector<std::vector<std::size_t>> neighbours(n);
  std::size_t comparisons = 0;
  auto similar = [&](std::size_t i, std::size_t j, std::size_t& count) {
    if (!bg::intersects(boxes[i], boxes[j])) return false;
    ++count;
    const double smaller = std::min(areas[i], areas[j]);
    if (smaller <= 0) return false;
    std::optional<double> inter = intersectionArea(polys[i], polys[j]);
    if (!inter) {  // degenerate (touching vertices, shared edges): Boost's robust overlay
      MPoly2 both;
      bg::intersection(bufferPiece(pieces[i], p.buffer_width),
                       bufferPiece(pieces[j], p.buffer_width), both);
      inter = bg::area(both);
    }
    return *inter >= p.min_overlap_ratio * smaller;
  };
#pragma omp parallel reduction(+ : comparisons)
  {
    std::vector<int> present, partners;
    std::vector<std::pair<std::size_t, std::size_t>> edges;
#pragma omp for schedule(dynamic, 16)
    for (std::ptrdiff_t t = 0; t < std::ptrdiff_t(tiles.size()); ++t) {
      const auto [b, e] = tiles[std::size_t(t)];
      // the tile's drives and the range of each (by_tile is sorted by drive within a tile)
      present.clear();
      std::vector<std::pair<std::size_t, std::size_t>> range;
      for (std::size_t r = b; r < e; ++r)
        if (r == b || driveOf(by_tile[r]) != driveOf(by_tile[r - 1])) {
          present.push_back(driveOf(by_tile[r]));
          range.emplace_back(r, r + 1);
        } else {
          range.back().second = r + 1;
        }
      edges.clear();
      const bool all = p.partner_drives <= 0 || int(present.size()) <= p.partner_drives + 1;
      for (std::size_t r = b; r < e; ++r) {
        const std::size_t i = by_tile[r];
        if (all) {  // every pair once
          for (std::size_t q = r + 1; q < e; ++q)
            if (similar(i, by_tile[q], comparisons)) edges.emplace_back(i, by_tile[q]);
          continue;
        }
        const uint64_t offset = uint64_t(driveOf(i)) + uint64_t(pieces[i].tile) * 40503ull;
        partnerDrives(present, driveOf(i), p.partner_drives, offset, partners);
        for (int d : partners) {
          const auto it = std::lower_bound(present.begin(), present.end(), d);
          const auto [qb, qe] = range[std::size_t(it - present.begin())];
          for (std::size_t q = qb; q < qe; ++q) {
            const std::size_t j = by_tile[q];
            if (j != i && similar(i, j, comparisons))
              edges.emplace_back(std::min(i, j), std::max(i, j));
          }
        }
      }
      for (const auto& [i, j] : edges) {
        neighbours[i].push_back(j);
        neighbours[j].push_back(i);
      }
      for (std::size_t r = b; r < e; ++r) {
        auto& l = neighbours[by_tile[r]];
        std::sort(l.begin(), l.end());
        l.erase(std::unique(l.begin(), l.end()), l.end());
      }
    }
  }
  result.stats.comparisons = comparisons;
  const int min_pts = std::max(1, std::min(p.min_pts, num_drives));
  const DbscanResult clusters = dbscan(neighbours, min_pts);
  result.stats.noise_pieces = std::size_t(clusters.num_noise);

  // ---- each cluster (a MultiLineString) -> a centreline fragment
  std::vector<Fragment> frags(std::size_t(clusters.num_clusters));
  for (std::size_t i = 0; i < n; ++i) {
    if (clusters.labels[i] < 0) continue;
    Fragment& f = frags[std::size_t(clusters.labels[i])];
    const auto r = resamplePolyline(pieces[i].points, p.resample_step);
    f.samples.insert(f.samples.end(), r.begin(), r.end());
    f.obs.insert(pieces[i].obs);
  }
  for (auto& f : frags) f.centreline = binnedCentreline(f.samples, p.station_step);

  mergeSideBySide(frags, p);
  absorbStubs(frags, p);
  result.stats.fragments = frags.size();

  // ---- stage 2: link fragment ends with the modified core-object rule
  const std::size_t m = frags.size();
  std::vector<End> ends(2 * m);
  std::vector<PointValue> end_points(2 * m);
  for (std::size_t f = 0; f < m; ++f)
    for (int w = 0; w < 2; ++w) {
      ends[2 * f + w] = endOf(frags[f], w);
      end_points[2 * f + w] = {P2(ends[2 * f + w].pos.x(), ends[2 * f + w].pos.y()), 2 * f + w};
    }
  const bgi::rtree<PointValue, bgi::rstar<16>> etree(end_points.begin(), end_points.end());
  const double cos_max = std::cos(p.link_angle_deg * M_PI / 180.0);
  const double reach = std::max(p.link_distance, p.link_lateral);
  auto follows = [&](const End& a, const End& b) {  // b lies ahead of a, facing back at it
    if (a.dir.dot(b.dir) > -cos_max) return false;
    const Eigen::Vector2d v = (b.pos - a.pos).head<2>();
    const double along = v.dot(a.dir);
    const double lateral = (v - along * a.dir).norm();
    return along >= -p.link_lateral && along <= p.link_distance && lateral <= p.link_lateral;
  };
  auto straight = [&](std::size_t e, std::size_t f) {
    return follows(ends[e], ends[f]) && follows(ends[f], ends[e]);
  };
  // curves too tight for the straight test (roundabouts): both ends' last kArcTail metres on
  // one circle, the gap along it within link_distance (arc_link.hpp)
  ArcLinkLimits arc;  // radius >= 4 m, residual <= 0.15 m
  arc.max_gap = p.link_distance;
  // each end's last kArcTail metres: from_end[e] starts at the end and runs inward, to_end[e]
  // the reverse
  std::vector<std::vector<Vec3>> from_end(2 * m), to_end(2 * m);
  for (std::size_t e = 0; e < 2 * m; ++e) {
    const auto& c = frags[e / 2].centreline;
    auto& t = from_end[e];
    double run = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      const std::size_t i = e % 2 == 0 ? k : c.size() - 1 - k;
      if (k > 0) run += (c[i] - t.back()).head<2>().norm();
      if (run > kArcTail) break;
      t.push_back(c[i]);
    }
    to_end[e].assign(t.rbegin(), t.rend());
  }
  auto onArc = [&](std::size_t e, std::size_t f) {
    return (ends[f].pos - ends[e].pos).head<2>().norm() <= p.link_distance &&
           continuesOnArc(to_end[e], from_end[f], arc);
  };
  std::vector<std::vector<std::size_t>> cand(2 * m);
  for (std::size_t e = 0; e < 2 * m; ++e) {
    const auto& q = ends[e].pos;
    const Box2 box(P2(q.x() - reach, q.y() - reach), P2(q.x() + reach, q.y() + reach));
    std::vector<PointValue> hits;
    etree.query(bgi::within(box), std::back_inserter(hits));
    for (const auto& h : hits) {
      const std::size_t f = h.second;
      if (f / 2 == e / 2) continue;
      if (straight(e, f) || (onArc(e, f) && onArc(f, e))) cand[e].push_back(f);
    }
    dropShadowed(ends, e, p.station_step, cand[e]);
    std::sort(cand[e].begin(), cand[e].end());
  }
  auto isCore = [&](std::size_t e) {
    const int size = 1 + int(cand[e].size());  // |N_eps| counts the end itself
    return p.link_min_pts <= size && size <= p.link_max_pts;
  };
  std::vector<long> link(2 * m, -1);
  for (std::size_t e = 0; e < 2 * m; ++e) {
    if (1 + int(cand[e].size()) > p.link_max_pts) ++result.stats.branch_ends;
    if (!isCore(e)) continue;
    for (std::size_t f : cand[e])
      if (isCore(f) && link[f] < 0 && link[e] < 0) {
        link[e] = long(f);
        link[f] = long(e);
        ++result.stats.links;
      }
  }

  // ---- walk the chains into instances
  std::vector<bool> used(m, false);
  auto walk = [&](std::size_t start, int entry) {
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
      if (from >= 0 && !straight(std::size_t(from), 2 * f + in)) {  // follow the arc, no chord
        const auto bridge =
            arcBridge(to_end[std::size_t(from)], from_end[2 * f + in], p.station_step);
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
    if (polylineLength(inst.centreline) < p.min_instance_length)
      ++result.stats.dropped_short;
    else
      result.instances.push_back(std::move(inst));
  };
  for (std::size_t f = 0; f < m; ++f)
    if (!used[f] && (link[2 * f] < 0 || link[2 * f + 1] < 0)) walk(f, link[2 * f] < 0 ? 0 : 1);
  for (std::size_t f = 0; f < m; ++f)  // closed loops
    if (!used[f]) walk(f, 0);
  return result;
}

}  // namespace mapfuse::aggregate
