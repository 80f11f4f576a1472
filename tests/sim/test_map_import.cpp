// Map worlds that cannot be simulated usefully (issue 20): ways without `type` are read as
// `virtual` with one warning per map; a world without true markings is an error (exit 3) unless
// allow_no_markings; line pieces sharing a node are one marking.
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/lanelet2_osm.hpp"
#include "mapfuse/sim/lanelet2_world.hpp"
#include "mapfuse/sim/map_world.hpp"
#include "sim/line_chains.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {

/// Two lanelets side by side as a CommonRoad conversion writes them: bounds without `type`.
/// With `typed_middle` the shared middle bound is a dashed line_thin (one true marking).
std::string commonRoadMap(bool typed_middle) {
  const std::string middle_tags =
      typed_middle ? "<tag k='type' v='line_thin'/><tag k='subtype' v='dashed'/>" : "";
  return R"(<?xml version='1.0' encoding='UTF-8'?>
<osm version='0.6' generator='commonroad'>
  <node id='-1' lat='49.0000000' lon='8.4000000'/>
  <node id='-2' lat='49.0009000' lon='8.4000000'/>
  <node id='-3' lat='49.0000000' lon='8.4000480'/>
  <node id='-4' lat='49.0009000' lon='8.4000480'/>
  <node id='-5' lat='49.0000000' lon='8.4000960'/>
  <node id='-6' lat='49.0009000' lon='8.4000960'/>
  <way id='-10'><nd ref='-1'/><nd ref='-2'/></way>
  <way id='-11'><nd ref='-3'/><nd ref='-4'/>)" +
         middle_tags + R"(</way>
  <way id='-12'><nd ref='-5'/><nd ref='-6'/></way>
  <relation id='-20'><member type='way' ref='-10' role='left'/><member type='way' ref='-11' role='right'/>
    <tag k='type' v='lanelet'/></relation>
  <relation id='-21'><member type='way' ref='-11' role='left'/><member type='way' ref='-12' role='right'/>
    <tag k='type' v='lanelet'/></relation>
</osm>
)";
}

int countOf(const std::string& text, const std::string& needle) {
  int n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
    ++n;
  return n;
}

MapInstance line(int64_t id, std::vector<Eigen::Vector3d> pts, LineStyle style) {
  MapInstance m;
  m.id = id;
  m.cls = CrowdClass::kLaneLine;
  m.attributes = {style, LineColor::kWhite};
  m.points = std::move(pts);
  return m;
}

}  // namespace

TEST_CASE("Map import: a world without true markings is an InputError unless allowed",
          "[sim][osm][import]") {
  const fs::path dir = test::tempDir("map_import_lib");
  test::writeText(dir / "untyped.osm", commonRoadMap(false));
  geo::GeoOrigin origin{49.0, 8.4, 110.0};
  try {
    sim::loadMapWorld((dir / "untyped.osm").string(), true, {}, &origin);
    FAIL("no error for a world without markings");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK_THAT(what, Catch::Contains("untyped.osm") && Catch::Contains("no true markings") &&
                         Catch::Contains("3 ways have no `type` tag") &&
                         Catch::Contains("--allow-no-markings"));
  }
  sim::MapWorldSettings allow;
  allow.allow_no_markings = true;
  const sim::World world = sim::loadMapWorld((dir / "untyped.osm").string(), true, allow, &origin);
  CHECK(world.lanes.size() == 2);
  CHECK(sim::trueMarkings(world) == 0);
  CHECK(world.stats.at("untyped_ways_as_virtual") == 3);
  // One typed line is enough.
  test::writeText(dir / "typed.osm", commonRoadMap(true));
  const sim::World typed = sim::loadMapWorld((dir / "typed.osm").string(), true, {}, &origin);
  CHECK(sim::trueMarkings(typed) == 1);
  CHECK(typed.stats.at("untyped_ways_as_virtual") == 2);
}

TEST_CASE("simulate: untyped ways warn once naming the count and no markings exit 3",
          "[sim][osm][import][app]") {
  const fs::path dir = test::tempDir("map_import_app");
  test::writeText(dir / "typed.osm", commonRoadMap(true));
  test::writeText(dir / "untyped.osm", commonRoadMap(false));
  auto run = [&](const std::string& map, const std::string& extra, const std::string& name) {
    return test::simulateTruthOn(dir, map, extra, name);
  };
  // Warning: exit 0, one line naming the 2 untyped ways.
  CHECK(run("typed.osm", "", "typed") == 0);
  const std::string warn = test::readText(dir / "typed.err");
  CHECK(countOf(warn, "have no `type` tag; read as `virtual`") == 1);
  CHECK_THAT(warn, Catch::Contains("2 ways have no `type` tag"));
  // No true markings: exit 3, the message names the file and the way out, nothing written.
  CHECK(run("untyped.osm", "", "untyped") == 3);
  const std::string err = test::readText(dir / "untyped.err");
  CHECK_THAT(err, Catch::Contains("untyped.osm") && Catch::Contains("no true markings") &&
                      Catch::Contains("--allow-no-markings"));
  CHECK_FALSE(fs::exists(dir / "untyped" / "simulate.summary.json"));
  // Asked for: exit 0 with the warning.
  CHECK(run("untyped.osm", "--allow-no-markings true", "allowed") == 0);
  CHECK_THAT(test::readText(dir / "allowed.err"), Catch::Contains("allowed by allow_no_markings"));
}

TEST_CASE("Line chains: pieces meeting end to end with equal attributes join", "[sim][import]") {
  using V = Eigen::Vector3d;
  std::vector<MapInstance> lines = {
      line(1, {V(0, 0, 0), V(5, 0, 0)}, LineStyle::kDashed),
      line(2, {V(10, 0, 0), V(5, 0, 0)}, LineStyle::kDashed),  // reversed piece
      line(3, {V(10, 0, 0), V(15, 0, 0)}, LineStyle::kDashed),
      line(4, {V(15, 0, 0), V(20, 0, 0)}, LineStyle::kSolid),  // style changes: no join
      // A fork: three ends meet at (0, 10): nothing joins there.
      line(5, {V(-5, 10, 0), V(0, 10, 0)}, LineStyle::kSolid),
      line(6, {V(0, 10, 0), V(5, 10, 0)}, LineStyle::kSolid),
      line(7, {V(0, 10, 0), V(5, 12, 0)}, LineStyle::kSolid),
      // A right angle does not run on.
      line(8, {V(0, 20, 0), V(5, 20, 0)}, LineStyle::kSolid),
      line(9, {V(5, 20, 0), V(5, 25, 0)}, LineStyle::kSolid),
  };
  // A circle of two halves (radius 5 around (5, 40)).
  std::vector<V> upper, lower;
  for (int k = 0; k <= 12; ++k) {
    const double a = 3.14159265358979 * k / 12;
    upper.push_back(V(5 - 5 * std::cos(a), 40 + 5 * std::sin(a), 0));
    lower.push_back(V(5 + 5 * std::cos(a), 40 - 5 * std::sin(a), 0));
  }
  lines.push_back(line(10, upper, LineStyle::kSolid));
  lines.push_back(line(11, lower, LineStyle::kSolid));
  const int joins = sim::joinLineChains(lines, 1e-3);
  CHECK(joins == 3);
  REQUIRE(lines.size() == 8);
  CHECK(lines[0].id == 1);
  CHECK(lines[0].source_ids == std::vector<int64_t>{1, 2, 3});
  REQUIRE(lines[0].points.size() == 4);
  CHECK((lines[0].points.back() - V(15, 0, 0)).norm() < 1e-12);
  CHECK(lines[1].id == 4);
  const MapInstance& loop = lines.back();
  CHECK(loop.source_ids == std::vector<int64_t>{10, 11});
  CHECK(loop.points.size() == 26);
  CHECK((loop.points.front() - loop.points.back()).norm() < 1e-12);
}

TEST_CASE("Map import: Lanelet2 content checks (same bounds, far nodes, /dev/zero)",
          "[sim][import][bad]") {
  const fs::path dir = test::tempDir("map_import_content");
  auto load = [&](const std::string& name, const std::string& xml) {
    test::writeText(dir / name, xml);
    geo::GeoOrigin origin{0, 0, 0};
    return sim::loadMapWorld((dir / name).string(), true, {}, &origin);
  };
  // A lanelet whose left bound is its right bound: refused by the reader, naming the lanelet
  // (tests/sim/test_lanelet2_content.cpp has the reader's other content checks).
  std::string same = commonRoadMap(true);
  same.replace(same.find("<member type='way' ref='-12' role='right'/>"), 43,
               "<member type='way' ref='-11' role='right'/>");
  CHECK_THROWS_WITH(load("same.osm", same),
                    Catch::Contains("same.osm: field 'relation -21 member right'"));
  // A stop line with a node 2,000 km away: no stop line (dropped with a warning), not a truth
  // of 2,000 km.
  std::string far = commonRoadMap(true);
  far.replace(far.find("</osm>"), 6, R"(<node id='-7' lat='49.0' lon='8.40'/>
  <node id='-8' lat='31.0' lon='8.40'/>
  <way id='-13'><nd ref='-7'/><nd ref='-8'/><tag k='type' v='stop_line'/></way></osm>)");
  const sim::World f = load("far.osm", far);
  CHECK(f.stats.at("stop_lines") == 0);
  CHECK_THAT(f.warnings.entries().begin()->second.first, Catch::Contains("way -13 (stop_line"));
  // On the other side of the Earth: beyond the coordinate bound every reader holds, refused.
  std::string antipode = far;
  antipode.replace(antipode.find("lat='31.0' lon='8.40'"), 21, "lat='-49.0' lon='-171.6'");
  try {
    load("antipode.osm", antipode);
    FAIL("accepted");
  } catch (const InputError& err) {
    CHECK_THAT(err.what(), Catch::Contains("antipode.osm: way -13 has a node at ENU") &&
                               Catch::Contains("beyond 10000000 m"));
  }
  // Not a regular file: exit 4 (IoError), before reading.
  geo::GeoOrigin origin{0, 0, 0};
  CHECK_THROWS_AS(sim::loadMapWorld("/dev/zero", true, {}, &origin), IoError);
}
