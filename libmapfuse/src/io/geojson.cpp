#include "mapfuse/io/geojson.hpp"

#include <cmath>

#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {
namespace {

double roundTo(double v, double scale) {
  return std::round(v * scale) / scale;
}

Json position(const geo::EnuConverter& enu, const Eigen::Vector3d& p) {
  const geo::LatLonAlt g = enu.toWgs84(p);
  return Json::array({roundTo(g.lon, 1e7), roundTo(g.lat, 1e7), roundTo(g.alt, 1e3)});
}

// Signed area of the ring in the EN plane; > 0 for counter-clockwise.
double signedArea(const std::vector<Eigen::Vector3d>& ring) {
  double a = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const auto& p = ring[i];
    const auto& q = ring[(i + 1) % ring.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

Json geometry(const MapInstance& inst, const geo::EnuConverter& enu) {
  Json coords = Json::array();
  switch (geometryKind(inst.cls)) {
    case GeometryKind::kPoint:
      return {{"type", "Point"}, {"coordinates", position(enu, inst.points.front())}};
    case GeometryKind::kLine:
      for (const auto& p : inst.points) coords.push_back(position(enu, p));
      return {{"type", "LineString"}, {"coordinates", coords}};
    case GeometryKind::kPlanar: {
      std::vector<Eigen::Vector3d> ring = inst.points;
      if (signedArea(ring) < 0) std::reverse(ring.begin(), ring.end());
      for (const auto& p : ring) coords.push_back(position(enu, p));
      coords.push_back(coords.front());
      return {{"type", "Polygon"}, {"coordinates", Json::array({coords})}};
    }
  }
  return nullptr;
}

}  // namespace

Json vectorMapToGeoJson(const VectorMap& map) {
  const geo::EnuConverter enu(map.origin);
  Json features = Json::array();
  for (const auto& inst : map.instances) {
    Json props = {{"id", inst.id},
                  {"class", crowdClassName(inst.cls)},
                  {"style", lineStyleName(inst.attributes.style)},
                  {"color", lineColorName(inst.attributes.color)},
                  {"height", inst.height},
                  {"support_drives", inst.support.drives},
                  {"support_observations", inst.support.observations}};
    features.push_back({{"type", "Feature"},
                        {"id", inst.id},
                        {"geometry", geometry(inst, enu)},
                        {"properties", std::move(props)}});
  }
  return {{"type", "FeatureCollection"}, {"features", std::move(features)}};
}

void writeGeoJson(const std::filesystem::path& path, const VectorMap& map) {
  writeBytesAtomic(path, vectorMapToGeoJson(map).dump() + "\n");
}

}  // namespace mapfuse::io
