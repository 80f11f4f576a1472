#include "mapfuse/eval/map_metrics_checks.hpp"

#include <Eigen/Geometry>
#include <cstdio>

namespace mapfuse::eval {

namespace {
Eigen::AlignedBox2d extentOf(const VectorMap& map) {
  Eigen::AlignedBox2d box;  // empty
  for (const auto& i : map.instances)
    for (const auto& p : i.points) box.extend(p.head<2>());
  return box;
}

std::string describe(const Eigen::AlignedBox2d& b) {
  char buf[160];
  std::snprintf(buf, sizeof(buf), "x %.0f..%.0f m, y %.0f..%.0f m", b.min().x(), b.max().x(),
                b.min().y(), b.max().y());
  return buf;
}
}  // namespace

std::vector<std::string> mapEvaluationProblems(const VectorMap& map, const std::string& map_file,
                                               const VectorMap& truth,
                                               const std::string& truth_file) {
  std::vector<std::string> problems;
  const Eigen::AlignedBox2d m = extentOf(map), t = extentOf(truth);
  if (t.isEmpty())
    problems.push_back(truth_file + ": the truth holds no element with points: nothing to score");
  if (m.isEmpty()) problems.push_back(map_file + ": the map holds no element with points");
  if (!t.isEmpty() && !m.isEmpty()) {
    Eigen::AlignedBox2d grown = t;
    grown.extend(t.min() - Eigen::Vector2d::Constant(kOverlapMargin));
    grown.extend(t.max() + Eigen::Vector2d::Constant(kOverlapMargin));
    if (!grown.intersects(m))
      problems.push_back(map_file + " and " + truth_file + " do not overlap (map " + describe(m) +
                         ", truth " + describe(t) +
                         " in the truth's ENU): another frame or origin?");
  }
  return problems;
}

}  // namespace mapfuse::eval
