#include "mapfuse/tiling/stitch.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/origin.hpp"

namespace mapfuse::tiling {

std::vector<ClippedPiece> clipPolyline(const std::vector<Eigen::Vector3d>& line, const Rect& r) {
  std::vector<ClippedPiece> pieces;
  ClippedPiece cur;
  bool open = false;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Eigen::Vector3d p0 = line[i], d = line[i + 1] - line[i];
    // Liang–Barsky: p_k t <= q_k for the four half-planes of the rectangle.
    double t0 = 0.0, t1 = 1.0;
    const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
    const double q[4] = {p0.x() - r.min_x, r.max_x - p0.x(), p0.y() - r.min_y, r.max_y - p0.y()};
    bool visible = true;
    for (int k = 0; k < 4 && visible; ++k) {
      if (p[k] == 0.0) {
        visible = q[k] >= 0.0;
      } else {
        const double t = q[k] / p[k];
        if (p[k] < 0)
          t0 = std::max(t0, t);
        else
          t1 = std::min(t1, t);
      }
    }
    if (!visible || t0 > t1) {
      if (open) pieces.push_back(cur), open = false;
      continue;
    }
    if (!open) {
      cur = ClippedPiece{};
      cur.points.push_back(p0 + t0 * d);
      cur.start_cut = t0 > 0.0 || i > 0;
      open = true;
    }
    cur.points.push_back(p0 + t1 * d);
    if (t1 < 1.0) {
      cur.end_cut = true;
      pieces.push_back(cur);
      open = false;
    }
  }
  if (open) pieces.push_back(cur);  // reached the line's own end inside the rectangle
  return pieces;
}

namespace {

struct Piece {
  MapInstance inst;  // geometry = clipped points
  std::size_t tile;
  bool cut[2];  // start, end
  bool whole;   // the original, unclipped line
};

struct Link {
  int piece = -1;
  int end = 0;
};

// Appends piece points oriented so that `first_end` comes first, merging the junction point.
void appendOriented(std::vector<Eigen::Vector3d>& out, const std::vector<Eigen::Vector3d>& pts,
                    int first_end) {
  std::vector<Eigen::Vector3d> p = pts;
  if (first_end == 1) std::reverse(p.begin(), p.end());
  std::size_t k = 0;
  if (!out.empty()) {
    out.back() = 0.5 * (out.back() + p.front());
    k = 1;
  }
  out.insert(out.end(), p.begin() + k, p.end());
}

// Joins line pieces through their cut ends, greedily by distance; returns the joined instances.
std::vector<MapInstance> joinPieces(std::vector<Piece>& pieces, const StitchParams& params,
                                    const BezierRefit& refit, StitchReport& report) {
  struct Candidate {
    double dist;
    int a, ea, b, eb;
  };
  std::vector<Candidate> cands;
  for (int a = 0; a < int(pieces.size()); ++a)
    for (int b = a + 1; b < int(pieces.size()); ++b) {
      if (pieces[a].tile == pieces[b].tile || pieces[a].inst.cls != pieces[b].inst.cls) continue;
      for (int ea = 0; ea < 2; ++ea)
        for (int eb = 0; eb < 2; ++eb) {
          if (!pieces[a].cut[ea] || !pieces[b].cut[eb]) continue;
          const auto& pa = ea ? pieces[a].inst.points.back() : pieces[a].inst.points.front();
          const auto& pb = eb ? pieces[b].inst.points.back() : pieces[b].inst.points.front();
          const double d = (pa - pb).head<2>().norm();
          if (d <= params.join_tolerance) cands.push_back({d, a, ea, b, eb});
        }
    }
  std::sort(cands.begin(), cands.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.dist, x.a, x.ea, x.b, x.eb) < std::tie(y.dist, y.a, y.ea, y.b, y.eb);
  });
  std::vector<std::array<Link, 2>> links(pieces.size());
  for (const auto& c : cands) {
    if (links[c.a][c.ea].piece >= 0 || links[c.b][c.eb].piece >= 0) continue;
    links[c.a][c.ea] = {c.b, c.eb};
    links[c.b][c.eb] = {c.a, c.ea};
    ++report.joins;
  }

  std::vector<MapInstance> out;
  std::vector<bool> visited(pieces.size(), false);
  auto walk = [&](int start, int first_end) {
    MapInstance joined = pieces[start].inst;
    joined.points.clear();
    joined.source_ids.clear();
    std::set<int64_t> sources;
    double longest = -1.0;
    int count = 0;
    bool all_whole = true;
    for (int cur = start, fe = first_end; cur >= 0 && !visited[cur];) {
      visited[cur] = true;
      const Piece& p = pieces[cur];
      appendOriented(joined.points, p.inst.points, fe);
      const double len = polylineLength(p.inst.points);
      if (len > longest) longest = len, joined.attributes = p.inst.attributes;
      joined.support.drives = std::max(joined.support.drives, p.inst.support.drives);
      joined.support.observations =
          std::max(joined.support.observations, p.inst.support.observations);
      sources.insert(p.inst.source_ids.begin(), p.inst.source_ids.end());
      all_whole = all_whole && p.whole;
      ++count;
      const Link next = links[cur][1 - fe];
      cur = next.piece;
      fe = next.end;
    }
    joined.source_ids.assign(sources.begin(), sources.end());
    if (!(count == 1 && all_whole))
      joined.bezier = refit ? refit(joined.points) : std::vector<BezierSegment>{};
    if (polylineLength(joined.points) >= params.min_piece_length) out.push_back(std::move(joined));
  };
  for (int i = 0; i < int(pieces.size()); ++i)
    for (int e = 0; e < 2; ++e)
      if (!visited[i] && links[i][e].piece < 0) walk(i, e);
  for (int i = 0; i < int(pieces.size()); ++i)
    if (!visited[i]) walk(i, 0);  // closed loops
  return out;
}

}  // namespace

VectorMap stitchTiles(const std::vector<std::pair<TileKey, VectorMap>>& tiles, const TileGrid& grid,
                      const StitchParams& params, StitchReport& report, const BezierRefit& refit) {
  report = StitchReport{};
  VectorMap out;
  out.source = "stitch";
  if (tiles.empty()) throw InputError("stitch: no tile maps given");
  out.origin = tiles.front().second.origin;
  std::vector<Piece> pieces;
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const auto& [key, map] = tiles[t];
    if (!geo::sameOrigin(map.origin, out.origin))
      throw InputError("stitch: tile " + key.name() + " has another ENU origin");
    ++report.tiles;
    const Rect core = grid.core(key);
    for (const auto& inst : map.instances) {
      ++report.instances_in;
      // Discrete elements, and stop lines (segments of a few metres, always whole inside the
      // margins): the tile that owns the centre keeps the element whole, never cut and rejoined.
      if (geometryKind(inst.cls) != GeometryKind::kLine || inst.cls == CrowdClass::kStopLine) {
        const Eigen::Vector3d c = instanceCentre(inst);
        if (core.ownsPoint(c.x(), c.y()))
          out.instances.push_back(inst);
        else
          ++report.dropped_outside_core;
        continue;
      }
      const auto clipped = clipPolyline(inst.points, core);
      for (const auto& cp : clipped) {
        Piece p{inst, t, {cp.start_cut, cp.end_cut}, !cp.start_cut && !cp.end_cut};
        p.inst.points = cp.points;
        pieces.push_back(std::move(p));
      }
    }
  }
  report.line_pieces = int(pieces.size());
  for (auto& inst : joinPieces(pieces, params, refit, report))
    out.instances.push_back(std::move(inst));

  // Deterministic order and fresh ids.
  std::stable_sort(out.instances.begin(), out.instances.end(),
                   [](const MapInstance& a, const MapInstance& b) {
                     const auto& pa = a.points.front();
                     const auto& pb = b.points.front();
                     return std::make_tuple(int(a.cls), pa.x(), pa.y()) <
                            std::make_tuple(int(b.cls), pb.x(), pb.y());
                   });
  for (std::size_t i = 0; i < out.instances.size(); ++i) out.instances[i].id = int64_t(i + 1);
  report.instances_out = int(out.instances.size());
  return out;
}

}  // namespace mapfuse::tiling
