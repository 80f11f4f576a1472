// Travel directions of lanelets from their oriented neighbours (lanelet/plan.hpp
// neighbourDirections; docs/formats.md "Lanelet2 export").
#include <cmath>
#include <map>

#include "mapfuse/lanelet/plan.hpp"

namespace mapfuse::lanelet {
namespace {

using V3 = Eigen::Vector3d;

/// Unit xy direction of a polyline at the vertex nearest p.
Eigen::Vector2d directionAt(const std::vector<V3>& line, const V3& p) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < line.size(); ++k)
    if ((line[k] - p).head<2>().squaredNorm() < (line[best] - p).head<2>().squaredNorm()) best = k;
  const std::size_t a = best > 0 ? best - 1 : 0, b = std::min(best + 1, line.size() - 1);
  const Eigen::Vector2d d = (line[b] - line[a]).head<2>();
  return d.norm() > 1e-9 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d::Zero();
}

}  // namespace

std::vector<std::pair<std::size_t, bool>> neighbourDirections(const LaneletPlan& plan,
                                                              const VectorMap& map) {
  // Lanelets by the pieces they are bounded by.
  std::multimap<std::size_t, std::size_t> by_piece;
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
    by_piece.insert({plan.lanelets[l].left, l});
    by_piece.insert({plan.lanelets[l].right, l});
  }
  std::map<std::size_t, int> verdict;  // lanelet -> +1 along its centre, -1 against, 0 disputed
  for (std::size_t k = 0; k < plan.lanelets.size(); ++k) {
    const auto& known = plan.lanelets[k];
    if (!known.direction_known) continue;
    for (const bool on_left : {true, false}) {
      const std::size_t piece = on_left ? known.left : known.right;
      const MapInstance& line = map.instances[plan.lines[plan.pieces[piece].line].instance];
      const bool centre_line =
          line.attributes.style == LineStyle::kSolid || line.attributes.color == LineColor::kYellow;
      if (on_left && !centre_line) continue;  // dashed white on the left: either way
      const auto range = by_piece.equal_range(piece);
      for (auto it = range.first; it != range.second; ++it) {
        const std::size_t u = it->second;
        if (u == k || plan.lanelets[u].direction_known) continue;
        const auto pts = piecePoints(plan, piece);
        const V3 mid = pts[pts.size() / 2];
        const double dot =
            directionAt(known.centre, mid).dot(directionAt(plan.lanelets[u].centre, mid));
        if (std::abs(dot) < 0.5) continue;  // not side by side here
        // Right neighbour: the same way; left neighbour across a centre line: the other way.
        const int along = (dot > 0) == !on_left ? 1 : -1;
        auto [v, fresh] = verdict.try_emplace(u, along);
        if (!fresh && v->second != along) v->second = 0;
      }
    }
  }
  std::vector<std::pair<std::size_t, bool>> out;
  for (const auto& [u, along] : verdict)
    if (along != 0) out.push_back({u, along > 0});
  return out;
}

}  // namespace mapfuse::lanelet
