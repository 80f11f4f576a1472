#include "lane_instantiation.hpp"

// Boost.Geometry buffer/rtree instantiations trigger GCC false positives.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <cmath>
#include <numeric>
#include <optional>
#include <tuple>

#include "box2d.hpp"
#include "crossing_lines.hpp"
#include "lane_fragments.hpp"
#include "lane_links.hpp"
#include "line_buffer.hpp"
#include "mapfuse/aggregate/dbscan.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/parallel_for.hpp"
#include "mapfuse/core/voxel_grid.hpp"
#include "mapfuse/io/bounds.hpp"
#include "partner_drives.hpp"
#include "polygon_overlap.hpp"

namespace mapfuse::aggregate {
using detail::partnerDrives;
namespace {

constexpr double kSimplifyTolerance = 0.02;  // m
// Piece budget of the tiling step: 64 pieces per observation on average (real drives: 2-4),
// and never less than 1e5 in all.
constexpr int64_t kPiecesPerObservation = 64;
constexpr int64_t kMinPieceBudget = 100000;

namespace bg = boost::geometry;
using Vec3 = Eigen::Vector3d;
using Line2 = bg::model::linestring<P2>;
using Poly2 = bg::model::polygon<P2>;
using MPoly2 = bg::model::multi_polygon<Poly2>;

struct Piece {
  std::size_t obs = 0;  ///< index into items
  int64_t tile = 0;
  Eigen::Vector2d corner{0, 0};  ///< lower-left corner of the tile (local origin of stage 1)
  std::vector<Vec3> points;
};

int64_t tileKey(const Vec3& p, double size) {
  return voxel_grid::cellKey2d(p.x(), p.y(), size);
}

// Pieces an observation gives at most (one per tile crossing of a segment, plus one per
// segment), counted without making them. Coordinates are within the readers' bounds
// (io/bounds.hpp), so the tile indices are exact integers.
int64_t piecesOf(const std::vector<Vec3>& pts, double size) {
  auto index = [&](double x) {
    const double i = std::floor(x / size);
    if (!(std::abs(i) < 1e15))
      throw InputError("lane observation coordinate " + io::bounds::numberText(x) +
                       " m has no tile of " + io::bounds::numberText(size) + " m");
    return int64_t(i);
  };
  int64_t pieces = 0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    for (int axis = 0; axis < 2; ++axis)
      pieces += std::llabs(index(pts[i][axis]) - index(pts[i - 1][axis]));
  return pieces + int64_t(pts.size());
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
      // Grid lines by integer index: `g += size` stops advancing once g is large against size
      // (one point at x = 1e308 looped forever).
      for (auto k = int64_t(std::ceil(lo / size)); double(k) * size < hi; ++k) {
        const double t = (double(k) * size - a[axis]) / d[axis];
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

// Tiling: the lane observations `indices` cut into pieces, each inside one tile (pieces too
// short for a line dropped).
std::vector<Piece> cutObservations(const std::vector<Observation>& items,
                                   const std::vector<std::size_t>& indices, double tile_size) {
  // Budget before allocating: a real observation crosses a few tiles (a marking seen from one
  // keyframe is tens of metres long); absurd geometry within the readers' bounds is refused here
  // instead of exhausting memory (one element reaching 1e8 m allocated 5.7 GB).
  const int64_t budget = kPiecesPerObservation * int64_t(indices.size()) + kMinPieceBudget;
  int64_t total = 0;
  std::size_t longest = indices.empty() ? 0 : indices.front();
  int64_t longest_pieces = 0;
  for (std::size_t idx : indices) {
    const int64_t n = piecesOf(items[idx].points, tile_size);
    total += n;
    if (n > longest_pieces) longest_pieces = n, longest = idx;
  }
  if (total > budget)
    throw InputError("lane observations would be cut into " + std::to_string(total) +
                     " pieces of " + io::bounds::numberText(tile_size) + " m tiles (limit " +
                     std::to_string(budget) + "): element " +
                     std::to_string(items[longest].element_id) + " of input LSM #" +
                     std::to_string(items[longest].drive + 1) + " (command-line order) crosses " +
                     std::to_string(longest_pieces) + " tiles");
  std::vector<Piece> pieces;
  for (std::size_t idx : indices) cutAtTiles(items[idx].points, tile_size, idx, pieces);
  pieces.erase(std::remove_if(pieces.begin(), pieces.end(),
                              [](const Piece& q) { return toLine(q.points).size() < 2; }),
               pieces.end());
  return pieces;
}

// Pieces ordered by tile, then by drive, and each tile's [begin, end) in that order.
struct TileOrder {
  std::vector<std::size_t> by_tile;
  std::vector<std::pair<std::size_t, std::size_t>> tiles;
};

TileOrder orderByTile(const std::vector<Observation>& items, const std::vector<Piece>& pieces) {
  const std::size_t n = pieces.size();
  TileOrder o;
  o.by_tile.resize(n);
  std::iota(o.by_tile.begin(), o.by_tile.end(), std::size_t(0));
  auto driveOf = [&](std::size_t i) { return items[pieces[i].obs].drive; };
  std::stable_sort(o.by_tile.begin(), o.by_tile.end(), [&](std::size_t a, std::size_t b) {
    return pieces[a].tile != pieces[b].tile ? pieces[a].tile < pieces[b].tile
                                            : driveOf(a) < driveOf(b);
  });
  for (std::size_t k = 0; k < n;) {
    std::size_t e = k;
    while (e < n && pieces[o.by_tile[e]].tile == pieces[o.by_tile[k]].tile) ++e;
    o.tiles.emplace_back(k, e);
    k = e;
  }
  return o;
}

// One tile's buffered pieces in tile-local coordinates, prepared for the exact overlap area (a
// thread's scratch, reused tile after tile); indexed by position in by_tile minus the tile's
// begin.
struct TilePolygons {
  std::vector<OverlapPolygon> polys;
  std::vector<double> areas;
  std::vector<Box2> boxes;
  std::vector<std::vector<Eigen::Vector2d>> lines;  // simplified pieces, for the angle test
  std::size_t b = 0;

  void prepare(const std::vector<Piece>& pieces, const std::vector<std::size_t>& by_tile,
               std::size_t begin, std::size_t end, double buffer_width) {
    b = begin;
    polys.assign(end - b, OverlapPolygon());
    areas.assign(end - b, 0.0);
    boxes.assign(end - b, Box2());
    lines.assign(end - b, {});
    for (std::size_t r = b; r < end; ++r) {
      const Piece& piece = pieces[by_tile[r]];
      // The buffer ring built directly (line_buffer.hpp); Boost's where that may differ.
      Line2 simple;
      bg::simplify(toLine(piece.points), simple, kSimplifyTolerance);
      std::vector<Eigen::Vector2d> line;
      for (const auto& q : simple) line.emplace_back(bg::get<0>(q), bg::get<1>(q));
      lines[r - b] = line;
      if (const auto ring = mitreBuffer(line, buffer_width)) {
        areas[r - b] = ringArea(*ring);
        polys[r - b] = OverlapPolygon({*ring}, piece.corner);
      } else {
        const MPoly2 buffered = bufferPiece(piece, buffer_width);
        areas[r - b] = bg::area(buffered);
        polys[r - b] = toOverlapPolygon(buffered, piece.corner);
      }
      boxes[r - b] = boxOf(piece.points, buffer_width);
    }
  }

  // Stage-1 eps test of the pieces at positions r and q: buffers overlapping by at least
  // min_overlap_ratio of the smaller, and not crossing lines. `count` counts the overlap tests.
  bool similar(const std::vector<Piece>& pieces, const std::vector<std::size_t>& by_tile,
               std::size_t r, std::size_t q, const LaneInstantiationParams& p,
               std::size_t& count) const {
    const std::size_t ri = r - b, qi = q - b;
    if (!bg::intersects(boxes[ri], boxes[qi])) return false;
    ++count;
    const double smaller = std::min(areas[ri], areas[qi]);
    if (smaller <= 0) return false;
    std::optional<double> inter = intersectionArea(polys[ri], polys[qi]);
    if (!inter) {  // degenerate (touching vertices, shared edges): Boost's robust overlay
      MPoly2 both;
      bg::intersection(bufferPiece(pieces[by_tile[r]], p.buffer_width),
                       bufferPiece(pieces[by_tile[q]], p.buffer_width), both);
      inter = bg::area(both);
    }
    if (*inter < p.min_overlap_ratio * smaller) return false;
    // Crossing lines overlap where they cross: not neighbours (crossing_lines.hpp).
    // the shorter piece's points against the longer piece
    const double max_angle = p.piece_angle_deg * M_PI / 180.0;
    const bool r_shorter = areas[ri] <= areas[qi];
    return !piecesCross(r_shorter ? lines[ri] : lines[qi], r_shorter ? lines[qi] : lines[ri],
                        2 * p.buffer_width, max_angle);
  }
};

// Stage-1 neighbours of every piece (sorted): the pieces of the same tile whose buffered
// polygons overlap by at least min_overlap_ratio of the smaller one. `comparisons_made`
// receives the number of overlap tests.
std::vector<std::vector<std::size_t>> overlapNeighbours(const std::vector<Observation>& items,
                                                        const std::vector<Piece>& pieces,
                                                        const LaneInstantiationParams& p,
                                                        std::size_t* comparisons_made) {
  const std::size_t n = pieces.size();
  // Candidates: pieces of the same tile whose boxes intersect (touching counts), of at most
  // `partner_drives` other drives per piece (partner_drives.hpp). Tile by tile: a piece's
  // neighbours all lie in its own tile, so tiles run in parallel without sharing lists, and a
  // tile's polygons live only while it is compared (all tiles' at once were a third of
  // aggregate's peak memory).
  const TileOrder order = orderByTile(items, pieces);
  const auto& by_tile = order.by_tile;
  auto driveOf = [&](std::size_t i) { return items[pieces[i].obs].drive; };
  std::vector<std::vector<std::size_t>> neighbours(n);
  std::size_t comparisons = 0;
#pragma omp parallel reduction(+ : comparisons)
  {
    std::vector<int> present, partners;
    std::vector<std::pair<std::size_t, std::size_t>> edges;
    TilePolygons tile;
#pragma omp for schedule(dynamic, 16)
    for (std::ptrdiff_t t = 0; t < std::ptrdiff_t(order.tiles.size()); ++t) {
      const auto [b, e] = order.tiles[std::size_t(t)];
      tile.prepare(pieces, by_tile, b, e, p.buffer_width);
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
            if (tile.similar(pieces, by_tile, r, q, p, comparisons))
              edges.emplace_back(i, by_tile[q]);
          continue;
        }
        const uint64_t offset = uint64_t(driveOf(i)) + uint64_t(pieces[i].tile) * 40503ull;
        partnerDrives(present, driveOf(i), p.partner_drives, offset, partners);
        for (int d : partners) {
          const auto it = std::lower_bound(present.begin(), present.end(), d);
          const auto [qb, qe] = range[std::size_t(it - present.begin())];
          for (std::size_t q = qb; q < qe; ++q) {
            const std::size_t j = by_tile[q];
            if (j != i && tile.similar(pieces, by_tile, r, q, p, comparisons))
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
  *comparisons_made = comparisons;
  return neighbours;
}

// Each stage-1 cluster (a MultiLineString) -> a fragment with its centreline.
std::vector<Fragment> clusterFragments(const std::vector<Piece>& pieces,
                                       const DbscanResult& clusters,
                                       const LaneInstantiationParams& p) {
  std::vector<Fragment> frags(std::size_t(clusters.num_clusters));
  std::vector<std::vector<std::size_t>> members(frags.size());  // piece order
  for (std::size_t i = 0; i < pieces.size(); ++i)
    if (clusters.labels[i] >= 0) members[std::size_t(clusters.labels[i])].push_back(i);
  parallelFor(frags.size(), [&](std::size_t c) {  // fragments are independent
    Fragment& f = frags[c];
    for (std::size_t i : members[c]) {
      const auto r = resamplePolyline(pieces[i].points, p.resample_step);
      f.samples.insert(f.samples.end(), r.begin(), r.end());
      f.obs.insert(pieces[i].obs);
    }
    f.centreline = binnedCentreline(f.samples, p.station_step);
  });
  return frags;
}

}  // namespace

LaneInstantiation instantiateLanes(const std::vector<Observation>& items,
                                   const std::vector<std::size_t>& indices,
                                   const LaneInstantiationParams& p, int num_drives) {
  LaneInstantiation result;
  std::vector<Piece> pieces = cutObservations(items, indices, p.tile_size);
  result.stats.pieces = pieces.size();
  if (pieces.empty()) return result;

  // stage 1: buffered polygons, overlap-area similarity, DBSCAN; clusters -> fragments
  const int min_pts = std::max(1, std::min(p.min_pts, num_drives));
  const DbscanResult clusters =
      dbscan(overlapNeighbours(items, pieces, p, &result.stats.comparisons), min_pts);
  result.stats.noise_pieces = std::size_t(clusters.num_noise);
  std::vector<Fragment> frags = clusterFragments(pieces, clusters, p);
  std::vector<Piece>().swap(pieces);  // in the fragments' samples now
  mergeSideBySide(frags, p);
  absorbStubs(frags, p);
  result.stats.fragments = frags.size();
  // Stage 2 reads only the centrelines: the samples (the largest part of stage 1's memory) go.
  for (Fragment& f : frags) std::vector<Eigen::Vector3d>().swap(f.samples);

  // stage 2: link fragment ends with the modified core-object rule, walk the chains
  const FragmentEnds ends(frags, p);
  std::vector<std::vector<std::size_t>> candidates(ends.size());
  for (std::size_t e = 0; e < ends.size(); ++e) candidates[e] = ends.candidates(e);
  const std::vector<long> link = linkEnds(candidates, p, result.stats);
  result.instances = chainFragments(frags, ends, link, p, result.stats);
  return result;
}

}  // namespace mapfuse::aggregate
