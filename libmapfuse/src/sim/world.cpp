#include "mapfuse/sim/world.hpp"

#include <cmath>

namespace mapfuse::sim {

double World::laneLength() const {
  double total = 0.0;
  for (const auto& l : lanes) total += polylineLength(l.centerline);
  return total;
}

MapInstance& World::addTruth(int64_t id, CrowdClass cls, Polyline points, const std::string& note) {
  MapInstance m;
  m.id = id;
  m.cls = cls;
  m.points = std::move(points);
  m.note = note;
  m.source_ids = {m.id};
  truth.instances.push_back(std::move(m));
  return truth.instances.back();
}

namespace {
Eigen::Vector3d direction(const Polyline& line, bool at_end) {
  const std::size_t n = line.size();
  const Eigen::Vector3d d = at_end ? line[n - 1] - line[n - 2] : line[1] - line[0];
  return d.normalized();
}
}  // namespace

WorldSummary summarize(const World& world) {
  WorldSummary s;
  s.name = world.name;
  s.lanes = world.lanes.size();
  s.lane_km = world.laneLength() / 1000.0;
  s.elements = world.truth.instances.size();
  for (const auto& m : world.truth.instances) ++s.elements_by_class[crowdClassName(m.cls)];
  s.lane_line_km = totalLineLength(world.truth, CrowdClass::kLaneLine) / 1000.0;
  s.stats = world.stats;
  s.warnings = world.warnings;
  return s;
}

void connectLanesByEndpoints(World& world, double tolerance) {
  for (auto& a : world.lanes) {
    a.successors.clear();
    for (std::size_t j = 0; j < world.lanes.size(); ++j) {
      const auto& b = world.lanes[j];
      if (&a == &b) continue;
      if ((a.centerline.back() - b.centerline.front()).norm() > tolerance) continue;
      if (direction(a.centerline, true).dot(direction(b.centerline, false)) < 0.5) continue;
      a.successors.push_back(j);
    }
  }
}

std::vector<Polyline> observablePieces(const MapInstance& instance, const DashPattern& dashes,
                                       double step) {
  if (geometryKind(instance.cls) != GeometryKind::kLine) return {instance.points};
  if (instance.attributes.style != LineStyle::kDashed || instance.cls != CrowdClass::kLaneLine)
    return {resample(instance.points, step)};
  // The arc lengths once for all dashes: per dash, a 100 km dashed line of 200,000 points cost
  // 8,000 passes over all of them (51 s of simulate, minutes under the sanitizers; issue 37).
  std::vector<Polyline> pieces;
  const std::vector<double> cum = arcLengths(instance.points);
  const double length = cum.empty() ? 0.0 : cum.back();
  const double period = dashes.dash + dashes.gap;
  for (double s = 0.0; s < length - 0.3; s += period) {
    const double e = std::min(length, s + dashes.dash);
    if (e - s < 0.3) break;
    pieces.push_back(subLine(instance.points, cum, s, e, step));
  }
  return pieces;
}

}  // namespace mapfuse::sim
