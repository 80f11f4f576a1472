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
  auto check = [&](io::Json d, const std::string& field) {
    io::writeDocument(dir / "bad.json", d);
    try {
      io::readVectorMap(dir / "bad.json");
      FAIL("accepted a malformed map at " << field);
    } catch (const ParseError& e) {
      CHECK(e.field() == field);
    }
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
  // The sign polygon ring is closed and counter-clockwise.
  const auto ring = g["features"][1]["geometry"]["coordinates"][0];
  REQUIRE(ring.size() == 5);
  CHECK(ring.front() == ring.back());
  CHECK(g["features"][0]["geometry"]["type"] == "LineString");
  CHECK(g["features"][0]["properties"]["style"] == "solid");
}
