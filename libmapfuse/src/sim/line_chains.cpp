#include "line_chains.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace mapfuse::sim {

namespace {

constexpr double kMinContinuation = 0.7071;  // cos 45 deg: the line must run on

/// One end of a line: instance index and which end (0 = front, 1 = back).
struct End {
  std::size_t line;
  int side;
};

Eigen::Vector3d endPoint(const MapInstance& m, int side) {
  return side == 0 ? m.points.front() : m.points.back();
}

// Unit direction pointing out of the line at an end (xy).
Eigen::Vector2d outward(const MapInstance& m, int side) {
  const auto& p = m.points;
  const std::size_t n = p.size();
  const Eigen::Vector3d d = side == 0 ? p[0] - p[1] : p[n - 1] - p[n - 2];
  const Eigen::Vector2d d2 = d.head<2>();
  return d2.norm() > 1e-12 ? Eigen::Vector2d(d2.normalized()) : Eigen::Vector2d::Zero();
}

}  // namespace

int joinLineChains(
    std::vector<MapInstance>& instances, double tolerance,
    const std::function<bool(const MapInstance&, int, const MapInstance&, int)>& may_join) {
  // Ends of lane lines, bucketed on a grid of `tolerance` cells.
  std::vector<End> ends;
  std::map<std::pair<int64_t, int64_t>, std::vector<std::size_t>> grid;
  auto cell = [&](const Eigen::Vector3d& p) {
    return std::make_pair(static_cast<int64_t>(std::floor(p.x() / tolerance)),
                          static_cast<int64_t>(std::floor(p.y() / tolerance)));
  };
  for (std::size_t i = 0; i < instances.size(); ++i) {
    if (instances[i].cls != CrowdClass::kLaneLine || instances[i].points.size() < 2) continue;
    for (int side = 0; side < 2; ++side) {
      grid[cell(endPoint(instances[i], side))].push_back(ends.size());
      ends.push_back({i, side});
    }
  }
  // partner[e]: the one other end meeting end e, or -1 (none, several, or not a continuation).
  std::vector<long> partner(ends.size(), -1);
  for (std::size_t e = 0; e < ends.size(); ++e) {
    const MapInstance& a = instances[ends[e].line];
    const Eigen::Vector3d p = endPoint(a, ends[e].side);
    const auto [cx, cy] = cell(p);
    std::vector<std::size_t> near;
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = grid.find({cx + dx, cy + dy});
        if (it == grid.end()) continue;
        for (std::size_t f : it->second)
          if (f != e && (endPoint(instances[ends[f].line], ends[f].side) - p).norm() <= tolerance)
            near.push_back(f);
      }
    if (near.size() != 1) continue;
    const std::size_t f = near.front();
    const MapInstance& b = instances[ends[f].line];
    if (ends[f].line == ends[e].line || !(a.attributes == b.attributes)) continue;
    if (outward(a, ends[e].side).dot(outward(b, ends[f].side)) > -kMinContinuation) continue;
    if (may_join && !may_join(a, ends[e].side, b, ends[f].side)) continue;
    partner[e] = static_cast<long>(f);
  }
  // Only mutual pairs join; walk each chain from a free end (or anywhere on a loop).
  auto endIndex = [](std::size_t line_rank, int side) { return 2 * line_rank + side; };
  std::map<std::size_t, std::size_t> rank;  // instance index -> position in `ends` / 2
  for (std::size_t e = 0; e < ends.size(); e += 2) rank[ends[e].line] = e / 2;
  auto next = [&](std::size_t e) -> long {
    const long f = partner[e];
    return f >= 0 && partner[static_cast<std::size_t>(f)] == static_cast<long>(e) ? f : -1;
  };
  std::set<std::size_t> used;
  std::vector<MapInstance> out;
  int joins = 0;
  auto walk = [&](std::size_t first_line, int entry_side) {
    MapInstance chain = instances[first_line];
    chain.source_ids.clear();
    std::size_t line = first_line;
    int side = entry_side;  // the end we entered this piece through
    while (true) {
      used.insert(line);
      const MapInstance& piece = instances[line];
      std::vector<Eigen::Vector3d> pts = piece.points;
      if (side == 1) std::reverse(pts.begin(), pts.end());
      if (line == first_line) {
        chain.points = pts;
      } else {
        chain.points.insert(chain.points.end(), pts.begin() + 1, pts.end());
        if (!piece.note.empty() && chain.note.find(piece.note) == std::string::npos)
          chain.note += (chain.note.empty() ? "" : "; ") + piece.note;
        ++joins;
      }
      chain.source_ids.insert(chain.source_ids.end(), piece.source_ids.begin(),
                              piece.source_ids.end());
      if (piece.source_ids.empty()) chain.source_ids.push_back(piece.id);
      const long f = next(endIndex(rank[line], 1 - side));
      if (f < 0) break;
      const std::size_t next_line = ends[static_cast<std::size_t>(f)].line;
      if (next_line == first_line) {  // a closed loop: close the polyline
        chain.points.push_back(chain.points.front());
        break;
      }
      if (used.count(next_line)) break;
      line = next_line;
      side = ends[static_cast<std::size_t>(f)].side;
    }
    chain.bezier.clear();
    out.push_back(std::move(chain));
  };
  for (std::size_t i = 0; i < instances.size(); ++i) {
    if (used.count(i)) continue;
    if (!rank.count(i)) {
      out.push_back(instances[i]);
      continue;
    }
    const bool front_free = next(endIndex(rank[i], 0)) < 0;
    const bool back_free = next(endIndex(rank[i], 1)) < 0;
    if (!front_free && !back_free) continue;  // inside a chain or on a loop: walked later
    walk(i, front_free ? 0 : 1);
  }
  for (std::size_t i = 0; i < instances.size(); ++i)  // loops without a free end
    if (!used.count(i) && rank.count(i)) walk(i, 0);
  // Keep the map's order: a chain sits where its first piece was.
  instances = std::move(out);
  return joins;
}

}  // namespace mapfuse::sim
