#include "mapfuse/lanelet/right_of_way.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>

namespace mapfuse::lanelet {
namespace {

constexpr double kStopBehind = 8.0;     // m before an approach's end where its stop line may cross
constexpr double kStopAhead = 10.0;     // m beyond its end (the unpaired tail of its lane lines)
constexpr double kStopStep = 0.5;       // m between the axis samples tested
constexpr double kStopHit = 0.75;       // m from a sample to the stop line
constexpr double kDrivenReach = 10.0;   // m from a free approach's end to a drive's path
constexpr double kParallelCos = 0.866;  // |cos| above it: parallel or opposite (< 30 deg)

using V3 = Eigen::Vector3d;

double segmentDistanceXY(const V3& p, const V3& a, const V3& b) {
  const Eigen::Vector2d ab = (b - a).head<2>(), ap = (p - a).head<2>();
  const double t = ab.squaredNorm() > 0 ? std::clamp(ap.dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0;
  return (ap - t * ab).norm();
}

double distanceToLineXY(const std::vector<V3>& line, const V3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < line.size(); ++k)
    best = std::min(best, segmentDistanceXY(p, line[k], line[k + 1]));
  return best;
}

/// The travel direction at a lanelet's end (unit, xy).
Eigen::Vector2d endDirection(const LaneletPlan::Lanelet& ll) {
  const std::size_t n = ll.centre.size();
  const Eigen::Vector2d d = (ll.centre[n - 1] - ll.centre[n >= 3 ? n - 3 : 0]).head<2>();
  return d.norm() > 1e-9 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d(1, 0);
}

using PieceKey = std::pair<std::size_t, std::size_t>;  // (line, cut)

/// No oriented lanelet continues it: none is bounded by the next pieces of both its bounds'
/// lines in the travel direction (the lane runs into an unmarked area, or only a sliver too
/// short for a drive sample follows).
bool endsUnfollowed(const LaneletPlan& plan, const LaneletPlan::Lanelet& ll,
                    const std::set<std::pair<PieceKey, PieceKey>>& oriented_bounds) {
  PieceKey next[2];
  for (const bool left : {true, false}) {
    const auto [piece, last] = boundEnd(plan, ll, left, true);
    const auto& pc = plan.pieces[piece];
    if (!last && pc.cut == 0) return true;
    if (last && pc.cut + 2 >= plan.lines[pc.line].cuts.size()) return true;
    next[left] = {pc.line, last ? pc.cut + 1 : pc.cut - 1};
  }
  return !oriented_bounds.count(std::minmax(next[0], next[1]));
}

struct Approach {
  std::size_t lanelet;
  std::optional<std::size_t> stop;  ///< the stop line across its end
  Eigen::Vector2d dir;
};

std::size_t findRoot(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

bool crossing(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::abs(a.dot(b)) < kParallelCos;
}

}  // namespace

std::vector<RightOfWayRule> deriveRightOfWay(const LaneletPlan& plan,
                                             const std::vector<RightOfWayStop>& stops,
                                             const std::vector<DrivePath>& drives,
                                             const LaneletSettings& settings) {
  // Approaches: one-way lanelets that no lanelet continues or that a connector leaves.
  std::set<std::pair<PieceKey, PieceKey>> oriented_bounds;  // of the oriented lanelets
  for (const auto& ll : plan.lanelets) {
    if (!ll.direction_known) continue;
    const auto& a = plan.pieces[ll.left];
    const auto& b = plan.pieces[ll.right];
    oriented_bounds.insert(std::minmax(PieceKey{a.line, a.cut}, PieceKey{b.line, b.cut}));
  }
  std::set<std::size_t> candidates;
  for (const auto& c : plan.connectors) candidates.insert(c.from);
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l)
    if (endsUnfollowed(plan, plan.lanelets[l], oriented_bounds)) candidates.insert(l);
  // ... and those a stop line crosses near their end (a lanelet may continue past a stop line).
  for (const RightOfWayStop& st : stops)
    for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
      const auto& ll = plan.lanelets[l];
      if (ll.centre.empty() || distanceToLineXY(st.points, ll.centre.back()) > kStopBehind)
        continue;
      for (std::size_t k = 0; k + 1 < st.points.size(); ++k) {
        const V3 d = st.points[k + 1] - st.points[k];
        const int n = std::max(1, static_cast<int>(std::ceil(d.head<2>().norm() / kStopStep)));
        for (int q = 0; q <= n && !candidates.count(l); ++q)
          if (insideRingXY(ll.ring, st.points[k] + d * q / n)) candidates.insert(l);
      }
    }
  std::vector<Approach> approaches;
  for (std::size_t l : candidates) {
    const auto& ll = plan.lanelets[l];
    if (!ll.direction_known || ll.centre.size() < 2) continue;
    Approach a{l, std::nullopt, endDirection(ll)};
    // Its stop line: the one nearest its end along its axis, from kStopBehind before the end to
    // kStopAhead beyond it (the marking may run on past the last lanelet).
    const V3 end = ll.centre.back(), dir(a.dir.x(), a.dir.y(), 0.0);
    double best = std::numeric_limits<double>::infinity();
    for (double t = -kStopBehind; t <= kStopAhead; t += kStopStep)
      for (std::size_t s = 0; s < stops.size(); ++s)
        if (std::abs(t) < best && distanceToLineXY(stops[s].points, end + t * dir) <= kStopHit)
          best = std::abs(t), a.stop = s;
    approaches.push_back(a);
  }

  // Intersections: single linkage of the approaches' ends.
  std::vector<std::size_t> parent(approaches.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t i = 0; i < approaches.size(); ++i)
    for (std::size_t j = i + 1; j < approaches.size(); ++j) {
      const V3& a = plan.lanelets[approaches[i].lanelet].centre.back();
      const V3& b = plan.lanelets[approaches[j].lanelet].centre.back();
      if ((a - b).head<2>().norm() <= settings.intersection_reach)
        parent[findRoot(parent, i)] = findRoot(parent, j);
    }
  std::map<std::size_t, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < approaches.size(); ++i) groups[findRoot(parent, i)].push_back(i);

  std::vector<RightOfWayRule> rules;
  for (const auto& [root, members] : groups) {
    (void)root;
    bool signalled = false;
    std::vector<const Approach*> stop, free;
    for (std::size_t i : members) {
      const Approach& a = approaches[i];
      if (a.stop) signalled |= stops[*a.stop].signalled;
      (a.stop ? stop : free).push_back(&a);
    }
    if (signalled || stop.empty()) continue;
    auto crossesStop = [&](const Approach* x) {
      return std::any_of(stop.begin(), stop.end(),
                         [&](const Approach* s) { return crossing(x->dir, s->dir); });
    };
    // A drive passed the approach's end in its direction.
    auto drivenThrough = [&](const Approach& a) {
      const V3& end = plan.lanelets[a.lanelet].centre.back();
      for (const auto& d : drives)
        for (std::size_t k = 0; k + 1 < d.size(); ++k) {
          const Eigen::Vector2d step = (d[k + 1] - d[k]).head<2>();
          if ((d[k] - end).head<2>().norm() <= kDrivenReach && step.norm() > 1e-6 &&
              step.normalized().dot(a.dir) > kParallelCos)
            return true;
        }
      return false;
    };
    RightOfWayRule rule;
    for (const Approach* a : stop) {
      rule.yield.push_back(a->lanelet);
      rule.yield_stop.push_back(*a->stop);
    }
    // A free approach parallel to every yielding one (a lane beside them whose stop line was not
    // mapped, a lane ending further down the road) decides nothing.
    // A crossing free approach no drive passed may have a stop line the crowd did not map: the
    // intersection is then left without a rule rather than given a wrong one.
    bool unsure = false;
    for (const Approach* f : free)
      if (crossesStop(f)) {
        rule.right_of_way.push_back(f->lanelet);
        unsure |= !drivenThrough(*f);
      }
    if (unsure) continue;
    if (rule.right_of_way.empty()) {
      if (!std::any_of(stop.begin(), stop.end(), crossesStop)) continue;  // no crossing
      rule.all_way_stop = true;
    }
    rules.push_back(std::move(rule));
  }
  return rules;
}

}  // namespace mapfuse::lanelet
