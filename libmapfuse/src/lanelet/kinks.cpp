#include "kinks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mapfuse::lanelet::detail {

namespace {

using V3 = Eigen::Vector3d;

constexpr double kCoincident = 1e-9;  // m; closer points are one (Lanelet2: product < 1e-20)

/// How much vertex i of `pts` violates the rule: 0 when it does not, else its curvature
/// (infinite for a coincident neighbour or a turn back).
double violation(const std::vector<V3>& pts, std::size_t i, double max_curvature) {
  const Eigen::Vector2d in = (pts[i] - pts[i - 1]).head<2>(), out = (pts[i + 1] - pts[i]).head<2>();
  if (in.norm() < kCoincident || out.norm() < kCoincident || in.dot(out) < 0.0)
    return std::numeric_limits<double>::infinity();
  const double k = mengerCurvature(pts[i - 1], pts[i], pts[i + 1]);
  return k > max_curvature ? k : 0.0;
}

/// Distance (xy) from p to the polyline.
double distanceTo(const std::vector<V3>& line, const V3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const Eigen::Vector2d a = line[k].head<2>(), d = line[k + 1].head<2>() - a;
    const double len2 = d.squaredNorm();
    const double u = len2 > 0 ? std::clamp((p.head<2>() - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + u * d - p.head<2>()).norm());
  }
  return best;
}

}  // namespace

double mengerCurvature(const V3& a, const V3& b, const V3& c) {
  const double area = 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
  const double product =
      (b - a).head<2>().norm() * (c - a).head<2>().norm() * (c - b).head<2>().norm();
  if (product < 1e-20) return std::numeric_limits<double>::infinity();
  return std::abs(4.0 * area / product);
}

std::vector<V3> removeKinks(const std::vector<V3>& line, double max_curvature, KinkRemoval* stats) {
  std::vector<V3> pts = line;
  std::vector<V3> dropped;
  while (pts.size() > 2) {
    std::size_t worst = 0;
    double worst_v = 0.0;
    for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
      const double v = violation(pts, i, max_curvature);
      if (v > worst_v) worst = i, worst_v = v;
    }
    if (worst == 0) break;
    dropped.push_back(pts[worst]);
    pts.erase(pts.begin() + static_cast<long>(worst));
  }
  if (stats) {
    stats->removed = static_cast<int>(dropped.size());
    stats->max_deviation = 0.0;
    for (const V3& p : dropped)
      stats->max_deviation = std::max(stats->max_deviation, distanceTo(pts, p));
  }
  return pts;
}

void removePieceKinks(LaneletPlan& plan, double max_curvature) {
  for (auto& line : plan.lines) {
    std::vector<V3> points = {line.points.front()};
    std::vector<std::size_t> cuts = {0};
    for (std::size_t c = 0; c + 1 < line.cuts.size(); ++c) {
      const std::vector<V3> piece(line.points.begin() + static_cast<long>(line.cuts[c]),
                                  line.points.begin() + static_cast<long>(line.cuts[c + 1]) + 1);
      KinkRemoval stats;
      const std::vector<V3> clean = removeKinks(piece, max_curvature, &stats);
      plan.kink_vertices_removed += stats.removed;
      plan.kink_max_deviation = std::max(plan.kink_max_deviation, stats.max_deviation);
      points.insert(points.end(), clean.begin() + 1, clean.end());
      cuts.push_back(points.size() - 1);
    }
    line.points = std::move(points);
    line.cuts = std::move(cuts);
  }
}

}  // namespace mapfuse::lanelet::detail
