#include "mapfuse/io/geojson.hpp"

#include <algorithm>
#include <cmath>

#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {
namespace {

constexpr double kLonLatScale = 1e7;  // 7 decimals, about 1 cm
constexpr double kAltScale = 1e3;     // 1 mm

double roundTo(double v, double scale) {
  return std::round(v * scale) / scale;
}

/// A position as written: lon, lat, alt rounded to the file's precision.
struct Position {
  double lon, lat, alt;
  bool sameXY(const Position& o) const { return lon == o.lon && lat == o.lat; }
};

Position position(const geo::EnuConverter& enu, const Eigen::Vector3d& p) {
  const geo::LatLonAlt g = enu.toWgs84(p);
  return {roundTo(g.lon, kLonLatScale), roundTo(g.lat, kLonLatScale), roundTo(g.alt, kAltScale)};
}

Json toJson(const Position& p) {
  return Json::array({p.lon, p.lat, p.alt});
}

// Twice the signed area in the lon/lat plane; > 0 for counter-clockwise (lon east, lat north).
double signedArea2(const std::vector<Position>& ring) {
  double a = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Position& p = ring[i];
    const Position& q = ring[(i + 1) % ring.size()];
    a += p.lon * q.lat - q.lon * p.lat;
  }
  return a;
}

double cross(const Position& o, const Position& a, const Position& b) {
  return (a.lon - o.lon) * (b.lat - o.lat) - (a.lat - o.lat) * (b.lon - o.lon);
}

// Closed segments ab and cd share a point (collinear overlaps included).
bool segmentsTouch(const Position& a, const Position& b, const Position& c, const Position& d) {
  const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  auto onSegment = [](const Position& p, const Position& q, const Position& r, double c) {
    return c == 0.0 && std::min(p.lon, q.lon) <= r.lon && r.lon <= std::max(p.lon, q.lon) &&
           std::min(p.lat, q.lat) <= r.lat && r.lat <= std::max(p.lat, q.lat);
  };
  return onSegment(a, b, c, d1) || onSegment(a, b, d, d2) || onSegment(c, d, a, d3) ||
         onSegment(c, d, b, d4);
}

// A ring (not closed) is simple when no two non-neighbouring edges touch and it has area.
bool isSimpleRing(const std::vector<Position>& ring) {
  const std::size_t n = ring.size();
  if (n < 3 || signedArea2(ring) == 0.0) return false;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // neighbours share a vertex
      if (segmentsTouch(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n])) return false;
    }
  return true;
}

// Convex hull (Andrew's monotone chain), counter-clockwise, without collinear points.
std::vector<Position> convexHull(std::vector<Position> pts) {
  std::sort(pts.begin(), pts.end(), [](const Position& a, const Position& b) {
    return a.lon < b.lon || (a.lon == b.lon && a.lat < b.lat);
  });
  if (pts.size() < 3) return pts;
  std::vector<Position> hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  return hull;
}

/// Sign plate: the point below the plate's centre at its bottom edge, the plate's horizontal
/// width and vertical height (m).
struct Plate {
  Eigen::Vector3d bottom_centre;
  double width = 0.0, height = 0.0;
};

Plate plateOf(const MapInstance& inst) {
  Plate p;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  double zmin = inst.points.front().z(), zmax = zmin;
  for (const auto& q : inst.points) {
    c += q;
    zmin = std::min(zmin, q.z());
    zmax = std::max(zmax, q.z());
  }
  c /= double(inst.points.size());
  for (const auto& a : inst.points)
    for (const auto& b : inst.points) p.width = std::max(p.width, (a - b).head<2>().norm());
  p.bottom_centre = {c.x(), c.y(), zmin};
  p.height = zmax - zmin;
  return p;
}

/// A LineString without repeated positions; a Point when fewer than 2 distinct ones remain.
Json lineString(const std::vector<Position>& pts) {
  std::vector<Position> distinct;
  for (const auto& p : pts)
    if (distinct.empty() || !distinct.back().sameXY(p)) distinct.push_back(p);
  if (distinct.size() < 2) return {{"type", "Point"}, {"coordinates", toJson(pts.front())}};
  Json coords = Json::array();
  for (const auto& p : distinct) coords.push_back(toJson(p));
  return {{"type", "LineString"}, {"coordinates", coords}};
}

/// A horizontal footprint as an RFC 7946 polygon (closed, counter-clockwise, valid under GEOS).
/// `note` tells when the outline had to be replaced: an outline that crosses itself after
/// rounding becomes its convex hull; one without area a LineString.
Json footprint(const MapInstance& inst, const geo::EnuConverter& enu, std::string* note) {
  std::vector<Position> ring;
  for (const auto& p : inst.points) {
    const Position q = position(enu, p);
    if (ring.empty() || !ring.back().sameXY(q)) ring.push_back(q);
  }
  while (ring.size() > 1 && ring.back().sameXY(ring.front())) ring.pop_back();
  if (!isSimpleRing(ring)) {
    const std::vector<Position> hull = convexHull(ring);
    if (hull.size() < 3) {
      *note = "outline without area written as a line";
      return lineString(ring);
    }
    *note = "self-intersecting outline written as its convex hull";
    ring = hull;
  }
  if (signedArea2(ring) < 0) std::reverse(ring.begin(), ring.end());
  Json coords = Json::array();
  for (const auto& p : ring) coords.push_back(toJson(p));
  coords.push_back(coords.front());
  return {{"type", "Polygon"}, {"coordinates", Json::array({coords})}};
}

}  // namespace

Json vectorMapToGeoJson(const VectorMap& map) {
  const geo::EnuConverter enu(map.origin);
  Json features = Json::array();
  for (const auto& inst : map.instances) {
    Json props = {{"id", inst.id},
                  {"class", crowdClassName(inst.cls)},
                  {"style", lineStyleName(inst.attributes.style)},
                  {"color", lineColorName(inst.attributes.color)}};
    Json geometry;
    std::string note;
    if (inst.cls == CrowdClass::kTrafficSign) {  // a vertical plate: a point with its size
      const Plate plate = plateOf(inst);
      geometry = {{"type", "Point"}, {"coordinates", toJson(position(enu, plate.bottom_centre))}};
      props["width"] = roundTo(plate.width, kAltScale);
      props["height"] = roundTo(plate.height, kAltScale);
    } else {
      switch (geometryKind(inst.cls)) {
        case GeometryKind::kPoint:
          geometry = {{"type", "Point"},
                      {"coordinates", toJson(position(enu, inst.points.front()))}};
          props["height"] = inst.height;
          break;
        case GeometryKind::kLine: {
          std::vector<Position> pts;
          for (const auto& p : inst.points) pts.push_back(position(enu, p));
          geometry = lineString(pts);
          break;
        }
        case GeometryKind::kPlanar: geometry = footprint(inst, enu, &note); break;
      }
    }
    props["support_drives"] = inst.support.drives;
    props["support_observations"] = inst.support.observations;
    if (inst.version != 1) props["version"] = inst.version;
    if (!note.empty()) props["geometry_note"] = note;
    features.push_back({{"type", "Feature"},
                        {"id", inst.id},
                        {"geometry", std::move(geometry)},
                        {"properties", std::move(props)}});
  }
  return {{"type", "FeatureCollection"}, {"features", std::move(features)}};
}

void writeGeoJson(const std::filesystem::path& path, const VectorMap& map) {
  writeBytesAtomic(path, vectorMapToGeoJson(map).dump() + "\n");
}

}  // namespace mapfuse::io
