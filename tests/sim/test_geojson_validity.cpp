// GeoJSON a GIS accepts (issue 20): every Polygon of the procedural world's map (the world the
// README demo drives), as is and with aggregation-like noise on every point, is closed, has at
// least 4 positions, is simple (no two non-neighbouring edges touch) and is wound
// counter-clockwise (RFC 7946 section 3.1.6); traffic signs, vertical plates, are Points with
// their size. The check here is written independently of io/geojson.cpp; tests/e2e/
// interop_formats.sh checks the aggregated demo map with GEOS as well.
#include <catch2/catch.hpp>
#include <random>

#include "mapfuse/io/geojson.hpp"
#include "mapfuse/sim/procedural_world.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {

struct XY {
  double x, y;
};

double orient(const XY& a, const XY& b, const XY& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool onSegment(const XY& a, const XY& b, const XY& p) {
  return orient(a, b, p) == 0.0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
         std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

bool touch(const XY& a, const XY& b, const XY& c, const XY& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
               o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  return onSegment(a, b, c) || onSegment(a, b, d) || onSegment(c, d, a) || onSegment(c, d, b);
}

/// Problems of one GeoJSON exterior ring; empty when valid.
std::string ringProblem(const io::Json& ring) {
  if (ring.size() < 4) return "fewer than 4 positions";
  if (ring.front() != ring.back()) return "not closed";
  std::vector<XY> p;
  for (const auto& c : ring) p.push_back({c[0].get<double>(), c[1].get<double>()});
  p.pop_back();  // the closing position
  const std::size_t n = p.size();
  double area2 = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    area2 += p[i].x * p[(i + 1) % n].y - p[(i + 1) % n].x * p[i].y;
  if (area2 <= 0.0) return area2 == 0.0 ? "no area" : "clockwise";
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;
      if (touch(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return "self-intersecting";
    }
  return "";
}

/// Checks every feature; returns the number of polygons checked.
int checkFeatures(const io::Json& g) {
  int polygons = 0;
  for (const auto& f : g["features"]) {
    const std::string type = f["geometry"]["type"];
    const std::string cls = f["properties"]["class"];
    INFO("feature " << f["id"] << " (" << cls << ")");
    if (cls == "traffic_sign") {
      CHECK(type == "Point");
      CHECK(f["properties"]["width"].get<double>() > 0.0);
      CHECK(f["properties"]["height"].get<double>() > 0.0);
    }
    if (type == "Polygon") {
      ++polygons;
      CHECK(ringProblem(f["geometry"]["coordinates"][0]).empty());
    } else if (type == "LineString") {
      const auto& c = f["geometry"]["coordinates"];
      CHECK(c.size() >= 2);
      for (std::size_t k = 1; k < c.size(); ++k) CHECK(c[k] != c[k - 1]);
    }
  }
  return polygons;
}

}  // namespace

TEST_CASE("GeoJSON of the procedural world: every polygon simple, closed, counter-clockwise",
          "[sim][geojson]") {
  const sim::World world =
      sim::buildProceduralWorld(sim::ProceduralParams{}, {49.0, 8.4, 110.0}, 1234);
  int signs = 0;
  for (const auto& m : world.truth.instances) signs += m.cls == CrowdClass::kTrafficSign;
  REQUIRE(signs > 0);
  const int polygons = checkFeatures(io::vectorMapToGeoJson(world.truth));
  CHECK(polygons > 10);
  // Aggregated maps carry noise: 5 cm horizontally and vertically on every point, 20 draws.
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (int draw = 0; draw < 20; ++draw) {
    VectorMap noisy = world.truth;
    for (auto& m : noisy.instances)
      for (auto& p : m.points) p += mapfuse::test::drawVector<Eigen::Vector3d>(noise, rng);
    CHECK(checkFeatures(io::vectorMapToGeoJson(noisy)) == polygons);
  }
}
