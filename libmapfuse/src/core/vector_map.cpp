#include "mapfuse/core/vector_map.hpp"

#include <unordered_set>

#include "mapfuse/core/error.hpp"

namespace mapfuse {

double polylineLength(const std::vector<Eigen::Vector3d>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

Eigen::Vector3d instanceCentre(const MapInstance& inst) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  if (geometryKind(inst.cls) == GeometryKind::kLine) {
    double length = 0.0;
    for (std::size_t i = 0; i + 1 < inst.points.size(); ++i) {
      const double l = (inst.points[i + 1] - inst.points[i]).norm();
      c += 0.5 * l * (inst.points[i] + inst.points[i + 1]);
      length += l;
    }
    if (length > 0.0) return c / length;
    c.setZero();
  }
  for (const auto& p : inst.points) c += p;
  return c / double(inst.points.size());
}

double totalLineLength(const VectorMap& map, CrowdClass cls) {
  double length = 0.0;
  for (const auto& inst : map.instances)
    if (inst.cls == cls) length += polylineLength(inst.points);
  return length;
}

void validateVectorMap(const VectorMap& map, const std::string& source) {
  auto fail = [&](const std::string& problem) { throw InputError(source + ": " + problem); };
  if (!geo::isValid(map.origin)) fail("origin is not a valid WGS84 point");
  std::unordered_set<int64_t> ids;
  for (std::size_t i = 0; i < map.instances.size(); ++i) {
    const auto& inst = map.instances[i];
    const std::string where = "instances[" + std::to_string(i) + "]";
    if (!ids.insert(inst.id).second) fail("duplicate instance id " + std::to_string(inst.id));
    const std::size_t n = inst.points.size();
    switch (geometryKind(inst.cls)) {
      case GeometryKind::kLine:
        if (n < 2) fail(where + ": a line needs at least 2 points");
        break;
      case GeometryKind::kPlanar:
        if (n < 3) fail(where + ": a polygon needs at least 3 points");
        break;
      case GeometryKind::kPoint:
        if (n != 1) fail(where + ": a point element needs exactly 1 point");
        break;
    }
    for (const auto& p : inst.points)
      if (!p.allFinite()) fail(where + ": non-finite coordinate");
  }
}

}  // namespace mapfuse
