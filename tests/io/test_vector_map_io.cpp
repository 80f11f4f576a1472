#include <catch2/catch.hpp>

#include "fixtures.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/geojson.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr double kExact = 1e-12;
constexpr double kGeoJsonTolerance = 0.02;  // m: 7 decimals of a degree is ~1 cm

// Writes `doc` to `path` and requires readVectorMap to refuse it naming `field`.
void expectRefusedAt(const std::filesystem::path& path, const io::Json& doc,
                     const std::string& field) {
  io::writeDocument(path, doc);
  try {
    io::readVectorMap(path);
    FAIL("accepted a malformed map at " << field);
  } catch (const ParseError& e) {
    CHECK(e.field() == field);
  }
}
}  // namespace

TEST_CASE("vector map round-trips through JSON and CBOR", "[io][vector_map]") {
  const auto dir = test::tempDir("vm-roundtrip");
  const VectorMap map = test::makeVectorMap();
  for (const char* name : {"m.json", "m.cbor"}) {
    io::writeVectorMap(dir / name, map);
    const VectorMap back = io::readVectorMap(dir / name);
    CHECK(back.source == map.source);
    CHECK(back.origin.lat == map.origin.lat);
    REQUIRE(back.instances.size() == map.instances.size());
    for (std::size_t i = 0; i < map.instances.size(); ++i) {
      const auto &a = map.instances[i], &b = back.instances[i];
      CHECK(a.id == b.id);
      CHECK(a.cls == b.cls);
      CHECK(a.attributes == b.attributes);
      CHECK(a.height == b.height);
      CHECK(a.support.drives == b.support.drives);
      CHECK(a.support.observations == b.support.observations);
      CHECK(a.source_ids == b.source_ids);
      CHECK(a.note == b.note);
      REQUIRE(a.points.size() == b.points.size());
      for (std::size_t k = 0; k < a.points.size(); ++k)
        CHECK((a.points[k] - b.points[k]).norm() < kExact);
      REQUIRE(a.bezier.size() == b.bezier.size());
    }
  }
}

TEST_CASE("compact maps drop lane samples and readers re-sample the Bezier chain",
          "[io][vector_map]") {
  const auto dir = test::tempDir("vm-compact");
  const VectorMap map = test::makeVectorMap();
  io::writeVectorMap(dir / "c.cbor", map, {true, 0.001});
  io::writeVectorMap(dir / "f.cbor", map);
  const VectorMap back = io::readVectorMap(dir / "c.cbor");
  const auto& lane = back.instances[0];
  REQUIRE(lane.points.size() >= 2);
  // Re-sampled points lie on the curve: first and last equal the chain ends.
  CHECK((lane.points.front() - Eigen::Vector3d(0, 0, 0)).norm() < 1e-3);
  CHECK((lane.points.back() - Eigen::Vector3d(9, 1, 0)).norm() < 1e-3);
  // Its length matches a fine sampling of the same chain within 1 %.
  const double fine = polylineLength(io::sampleBezierChain(map.instances[0].bezier, 0.01));
  CHECK(polylineLength(lane.points) == Approx(fine).epsilon(0.01));
  CHECK(std::filesystem::file_size(dir / "c.cbor") < std::filesystem::file_size(dir / "f.cbor"));
}

TEST_CASE("compact CBOR stores integer quanta and reads back exactly the rounded coordinates",
          "[io][vector_map]") {
  constexpr double kQuantum = 1.0 / 256.0;  // m, aggregate's default
  const auto dir = test::tempDir("vm-quanta");
  VectorMap map = test::makeVectorMap();
  // A second segment sharing the first one's end point: a chain of 7 control points.
  auto& lane = map.instances[0];
  const Eigen::Vector3d end = lane.bezier.back()[3];
  lane.bezier.push_back({end, end + Eigen::Vector3d(1.003, 0.2, 0.01),
                         end + Eigen::Vector3d(2.5, 0.7, 0.02),
                         end + Eigen::Vector3d(4.2, 1.1, 0)});
  const auto json = io::vectorMapToJson(map, {true, kQuantum});
  CHECK(json.at("quantum") == kQuantum);
  CHECK(json["instances"][0].at("bezier_q").size() == 7 * 3);  // shared end point once
  CHECK(json["instances"][2].contains("points_q"));
  io::writeVectorMap(dir / "q.cbor", map, {true, kQuantum});
  const VectorMap back = io::readVectorMap(dir / "q.cbor");
  auto rounded = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3d((p / kQuantum).array().round().matrix() * kQuantum);
  };
  REQUIRE(back.instances.size() == map.instances.size());
  REQUIRE(back.instances[0].bezier.size() == 2);
  for (std::size_t s = 0; s < 2; ++s)
    for (int k = 0; k < 4; ++k)
      CHECK((back.instances[0].bezier[s][k] - rounded(map.instances[0].bezier[s][k])).norm() <
            kExact);
  for (std::size_t i = 1; i < map.instances.size(); ++i) {
    REQUIRE(back.instances[i].points.size() == map.instances[i].points.size());
    for (std::size_t k = 0; k < map.instances[i].points.size(); ++k)
      CHECK((back.instances[i].points[k] - rounded(map.instances[i].points[k])).norm() < kExact);
  }
  // Segments that do not meet are kept as separate segments ("bezier"), never joined.
  lane.bezier[1][0] += Eigen::Vector3d(0.5, 0, 0);
  const auto apart = io::vectorMapToJson(map, {true, kQuantum});
  CHECK(apart["instances"][0].contains("bezier"));
  CHECK_FALSE(apart["instances"][0].contains("bezier_q"));
}

TEST_CASE("malformed compact coordinates are refused with the field", "[io][vector_map]") {
  const auto dir = test::tempDir("vm-quanta-bad");
  const auto good = io::vectorMapToJson(test::makeVectorMap(), {true, 0.01});
  auto check = [&](const io::Json& d, const std::string& field) {
    expectRefusedAt(dir / "bad.cbor", d, field);
  };
  auto d = good;
  d.erase("quantum");
  check(d, "instances[0].bezier_q");
  d = good;
  d["quantum"] = -1.0;
  check(d, "quantum");
  d = good;
  d["instances"][0]["bezier_q"].erase(0);  // not whole points
  check(d, "instances[0].bezier_q");
  d = good;
  for (int k = 0; k < 3; ++k) d["instances"][0]["bezier_q"].push_back(1);  // 5 control points
  check(d, "instances[0].bezier_q");
  d = good;
  d["instances"][2]["points_q"][0] = 0.5;  // not an integer
  check(d, "instances[2].points_q[0]");
}

TEST_CASE("Bezier evaluation matches the Bernstein form", "[io][vector_map]") {
  const BezierSegment b{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 0),
                        Eigen::Vector3d(3, 2, 0), Eigen::Vector3d(4, 0, 0)};
  // B(0.5) = (P0 + 3 P1 + 3 P2 + P3) / 8
  CHECK((io::bezierPoint(b, 0.5) - Eigen::Vector3d(2.0, 1.5, 0)).norm() < kExact);
  CHECK((io::bezierPoint(b, 0.0) - b[0]).norm() < kExact);
  CHECK((io::bezierPoint(b, 1.0) - b[3]).norm() < kExact);
}

TEST_CASE("malformed vector maps are refused", "[io][vector_map]") {
  const auto dir = test::tempDir("vm-malformed");
  const auto good = io::vectorMapToJson(test::makeVectorMap());
  auto check = [&](const io::Json& d, const std::string& field) {
    expectRefusedAt(dir / "bad.json", d, field);
  };
  auto d = good;
  d["instances"][1]["bezier"] = io::Json::array({io::Json::array({{0, 0, 0}, {1, 1, 1}})});
  check(d, "instances[1].bezier[0]");
  d = good;
  d["origin"]["lat"] = 123.0;
  check(d, "origin.lat");
  d = good;
  d["instances"][2]["points"][0] = {1, 2};
  check(d, "instances[2].points[0]");
  d = good;
  d["instances"][0]["class"] = 5;
  check(d, "instances[0].class");
  d = good;
  d["instances"][2]["points"] = io::Json::array({{0, 0, 0}, {1, 1, 1}});  // a pole with 2 points
  io::writeDocument(dir / "bad2.json", d);
  CHECK_THROWS_AS(io::readVectorMap(dir / "bad2.json"), InputError);
}

TEST_CASE("GeoJSON export is RFC 7946: lon/lat order, 7 decimals, closed CCW rings",
          "[io][geojson]") {
  const VectorMap map = test::makeVectorMap();
  const io::Json g = io::vectorMapToGeoJson(map);
  REQUIRE(g["type"] == "FeatureCollection");
  REQUIRE(g["features"].size() == 3);
  const geo::EnuConverter enu(map.origin);
  // The pole is a Point at the ENU position converted back to WGS84.
  const auto& pole = g["features"][2];
  CHECK(pole["geometry"]["type"] == "Point");
  const auto c = pole["geometry"]["coordinates"];
  const Eigen::Vector3d back =
      enu.toEnu({c[1].get<double>(), c[0].get<double>(), c[2].get<double>()});
  CHECK((back - map.instances[2].points[0]).norm() < kGeoJsonTolerance);
  CHECK(pole["properties"]["class"] == "pole");
  CHECK(pole["properties"]["height"] == 5.0);
  // At most 7 decimals.
  const double lon = c[0].get<double>();
  CHECK(std::abs(lon * 1e7 - std::round(lon * 1e7)) < 1e-3);
  // The sign is a vertical plate: a Point at the bottom centre with its width and height.
  const auto& sign = g["features"][1];
  REQUIRE(sign["geometry"]["type"] == "Point");
  const auto sc = sign["geometry"]["coordinates"];
  const Eigen::Vector3d sign_back =
      enu.toEnu({sc[1].get<double>(), sc[0].get<double>(), sc[2].get<double>()});
  CHECK((sign_back - Eigen::Vector3d(10, 5.3, 2)).norm() < kGeoJsonTolerance);
  CHECK(sign["properties"]["width"].get<double>() == Approx(0.6).margin(1e-3));
  CHECK(sign["properties"]["height"].get<double>() == Approx(0.6).margin(1e-3));
  CHECK(g["features"][0]["geometry"]["type"] == "LineString");
  CHECK(g["features"][0]["properties"]["style"] == "solid");
}

namespace {
/// Twice the signed area of a closed GeoJSON ring in the lon/lat plane (> 0: counter-clockwise).
double ringArea2(const io::Json& ring) {
  double a = 0.0;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i)
    a += ring[i][0].get<double>() * ring[i + 1][1].get<double>() -
         ring[i + 1][0].get<double>() * ring[i][1].get<double>();
  return a;
}
}  // namespace

TEST_CASE("GeoJSON footprints: clockwise outlines turn, crossing ones become their hull",
          "[io][geojson]") {
  VectorMap map = test::makeVectorMap();
  MapInstance arrow;  // clockwise square
  arrow.id = 4;
  arrow.cls = CrowdClass::kGroundArrow;
  arrow.points = {{0, 0, 0}, {0, 2, 0}, {2, 2, 0}, {2, 0, 0}};
  MapInstance bowtie;  // crosses itself: 0-1 and 2-3 intersect
  bowtie.id = 5;
  bowtie.cls = CrowdClass::kCrosswalk;
  bowtie.points = {{0, 0, 0}, {4, 3, 0}, {4, 0, 0}, {0, 3, 0}};
  MapInstance sliver;  // a repeated point after rounding: 2 distinct positions, no area
  sliver.id = 6;
  sliver.cls = CrowdClass::kCrosswalk;
  sliver.points = {{0, 0, 0}, {0, 0.0001, 0}, {3, 0, 0}};
  map.instances = {arrow, bowtie, sliver};
  const io::Json g = io::vectorMapToGeoJson(map);
  const auto& square = g["features"][0]["geometry"];
  REQUIRE(square["type"] == "Polygon");
  CHECK(square["coordinates"][0].size() == 5);
  CHECK(ringArea2(square["coordinates"][0]) > 0);
  const auto& hull = g["features"][1];
  REQUIRE(hull["geometry"]["type"] == "Polygon");
  CHECK(hull["geometry"]["coordinates"][0].size() == 5);  // the 4 corners of the bow tie's hull
  CHECK(ringArea2(hull["geometry"]["coordinates"][0]) > 0);
  CHECK(hull["properties"]["geometry_note"].get<std::string>().find("convex hull") !=
        std::string::npos);
  CHECK(g["features"][2]["geometry"]["type"] == "LineString");
}
