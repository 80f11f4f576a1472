#include "joins.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mapfuse::lanelet::detail {

namespace {

using V3 = Eigen::Vector3d;
using V2 = Eigen::Vector2d;

constexpr double kDirectionReach = 2.0;  // m back from an end over which its direction is taken
constexpr double kFacing = 0.9063;       // cos 25 deg: the ends' directions nearly opposite
constexpr double kMaxAcross = 0.5;       // m; lane lines are at least a lane width (2 m) apart

/// One end of a line: its point and outward unit direction (xy).
struct End {
  std::size_t line;
  bool back;  ///< the line's last point (else its first)
  V3 p;
  V2 out;
};

End endOf(const std::vector<V3>& line, std::size_t index, bool back) {
  const std::size_t n = line.size();
  const auto at = [&](std::size_t k) { return back ? line[n - 1 - k] : line[k]; };
  const V3 p = at(0);
  std::size_t k = 1;
  while (k + 1 < n && (at(k) - p).head<2>().norm() < kDirectionReach) ++k;
  const V2 d = (p - at(k)).head<2>();
  return {index, back, p, d.norm() > 1e-9 ? V2(d.normalized()) : V2(0, 0)};
}

/// Distance between two ends when they continue each other within max_join, else infinity.
double joinDistance(const End& a, const End& b, double max_join) {
  if (a.line == b.line || -a.out.dot(b.out) < kFacing)
    return std::numeric_limits<double>::infinity();
  const V2 v = (b.p - a.p).head<2>();
  const double across_a = std::abs(a.out.x() * v.y() - a.out.y() * v.x());
  const double across_b = std::abs(b.out.x() * v.y() - b.out.y() * v.x());
  if (std::abs(v.dot(a.out)) > max_join || std::abs(v.dot(b.out)) > max_join ||
      std::max(across_a, across_b) > kMaxAcross)
    return std::numeric_limits<double>::infinity();
  return v.norm();
}

/// The line with its end moved to j: vertices at or beyond j (along the end's outward
/// direction) dropped, then j. Empty when fewer than one vertex would stay before j.
std::vector<V3> endAt(std::vector<V3> line, const End& e, const V3& j) {
  if (!e.back) std::reverse(line.begin(), line.end());
  while (!line.empty() && (line.back() - j).head<2>().dot(e.out) >= -1e-9) line.pop_back();
  if (line.empty()) return {};
  line.push_back(j);
  if (!e.back) std::reverse(line.begin(), line.end());
  return line;
}

/// For each end, the index of its nearest joinable end (or -1).
std::vector<long> nearestPartners(const std::vector<End>& ends, double max_join) {
  using Cell = std::pair<long, long>;
  const double cell = std::max(max_join, 1.0) + kMaxAcross;
  auto cellOf = [&](const V3& p) {
    return Cell{static_cast<long>(std::floor(p.x() / cell)),
                static_cast<long>(std::floor(p.y() / cell))};
  };
  std::map<Cell, std::vector<std::size_t>> grid;
  for (std::size_t k = 0; k < ends.size(); ++k) grid[cellOf(ends[k].p)].push_back(k);
  std::vector<long> best(ends.size(), -1);
  for (std::size_t k = 0; k < ends.size(); ++k) {
    double best_d = std::numeric_limits<double>::infinity();
    const Cell c = cellOf(ends[k].p);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy) {
        const auto it = grid.find({c.first + dx, c.second + dy});
        if (it == grid.end()) continue;
        for (std::size_t o : it->second) {
          const double d = joinDistance(ends[k], ends[o], max_join);
          if (d < best_d) best_d = d, best[k] = static_cast<long>(o);
        }
      }
  }
  return best;
}

}  // namespace

LineJoins joinLineEnds(std::vector<std::vector<V3>>& lines, double max_join) {
  LineJoins stats;
  if (max_join <= 0.0) return stats;
  std::vector<End> ends;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].size() < 2) continue;
    ends.push_back(endOf(lines[i], i, false));
    ends.push_back(endOf(lines[i], i, true));
  }
  const std::vector<long> best = nearestPartners(ends, max_join);
  for (std::size_t k = 0; k < ends.size(); ++k) {
    const long o = best[k];
    if (o < 0 || o > static_cast<long>(k) ||
        best[static_cast<std::size_t>(o)] != static_cast<long>(k))
      continue;  // mutual nearest ends only, each pair once (from its higher index)
    const End& a = ends[k];
    const End& b = ends[static_cast<std::size_t>(o)];
    const V3 j = 0.5 * (a.p + b.p);
    // the ends as they are now (the other end of the line may have moved already)
    const End a_now = endOf(lines[a.line], a.line, a.back);
    const End b_now = endOf(lines[b.line], b.line, b.back);
    std::vector<V3> la = endAt(lines[a.line], a_now, j), lb = endAt(lines[b.line], b_now, j);
    if (la.size() < 2 || lb.size() < 2) continue;
    const double along = (b.p - a.p).head<2>().dot(a.out);  // > 0: a gap, < 0: an overlap
    (along >= 0 ? stats.max_gap : stats.max_overlap) =
        std::max(along >= 0 ? stats.max_gap : stats.max_overlap, std::abs(along));
    lines[a.line] = std::move(la);
    lines[b.line] = std::move(lb);
    ++stats.joined;
  }
  return stats;
}

}  // namespace mapfuse::lanelet::detail
