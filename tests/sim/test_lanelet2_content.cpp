// Lanelet2 map content checks (issue 37, docs/formats.md "Map content checks"): what the reader
// refuses (duplicate ids, references to missing elements, a lanelet whose left bound is its
// right bound, coordinates outside the value bounds) and what the world drops with a warning
// (ways whose nodes lie at one place). One small hand-written map, changed one fault at a time.
#include <catch2/catch.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/lanelet2_osm.hpp"
#include "mapfuse/sim/lanelet2_world.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
/// Two lanelets in a row (3.7 m wide, 11 m long each), the second with a traffic light
/// regulatory element (the light's way, its stop line).
const char* kMap = R"(<?xml version='1.0' encoding='UTF-8'?>
<osm version='0.6' generator='test'>
  <node id='-1' lat='49.0000000' lon='8.4000000'/>
  <node id='-2' lat='49.0001000' lon='8.4000000'/>
  <node id='-3' lat='49.0002000' lon='8.4000000'/>
  <node id='-4' lat='49.0000000' lon='8.4000500'/>
  <node id='-5' lat='49.0001000' lon='8.4000500'/>
  <node id='-6' lat='49.0002000' lon='8.4000500'/>
  <node id='-8' lat='49.0002100' lon='8.4000600'/>
  <node id='-9' lat='49.0002100' lon='8.4000700'/>
  <way id='-10'><nd ref='-1'/><nd ref='-2'/><tag k='type' v='line_thin'/><tag k='subtype' v='solid'/></way>
  <way id='-11'><nd ref='-2'/><nd ref='-3'/><tag k='type' v='line_thin'/><tag k='subtype' v='solid'/></way>
  <way id='-12'><nd ref='-4'/><nd ref='-5'/><tag k='type' v='line_thin'/><tag k='subtype' v='dashed'/></way>
  <way id='-13'><nd ref='-5'/><nd ref='-6'/><tag k='type' v='line_thin'/><tag k='subtype' v='dashed'/></way>
  <way id='-14'><nd ref='-3'/><nd ref='-6'/><tag k='type' v='stop_line'/></way>
  <way id='-15'><nd ref='-8'/><nd ref='-9'/><tag k='type' v='traffic_light'/></way>
  <relation id='-20'><member type='way' ref='-10' role='left'/><member type='way' ref='-12' role='right'/>
    <tag k='type' v='lanelet'/><tag k='subtype' v='road'/></relation>
  <relation id='-21'><member type='way' ref='-11' role='left'/><member type='way' ref='-13' role='right'/>
    <member type='relation' ref='-30' role='regulatory_element'/>
    <tag k='type' v='lanelet'/><tag k='subtype' v='road'/></relation>
  <relation id='-30'><member type='way' ref='-15' role='refers'/><member type='way' ref='-14' role='ref_line'/>
    <tag k='type' v='regulatory_element'/><tag k='subtype' v='traffic_light'/></relation>
</osm>
)";

/// `map` (kMap by default) with the first occurrence of `from` replaced by `to`.
std::string with(const std::string& from, const std::string& to, std::string map = kMap) {
  const std::size_t at = map.find(from);
  REQUIRE(at != std::string::npos);
  return map.replace(at, from.size(), to);
}

/// The ParseError message of reading `xml`, or "" when it is read.
std::string refusal(const std::string& xml) {
  try {
    io::parseLanelet2Osm(xml, "c.osm");
  } catch (const ParseError& e) {
    return e.what();
  }
  return "";
}

sim::World worldOf(const std::string& xml) {
  const io::Lanelet2Map map = io::parseLanelet2Osm(xml, "c.osm");
  return sim::worldFromLanelet2(map, *map.first_node);
}
}  // namespace

TEST_CASE("Lanelet2 content: the unchanged map is read whole", "[sim][osm][content]") {
  const io::Lanelet2Map map = io::parseLanelet2Osm(kMap, "c.osm");
  CHECK(map.node_count == 8);
  CHECK(map.linestrings.size() == 6);
  CHECK(map.lanelets.size() == 2);
  REQUIRE(map.regulatory_elements.size() == 1);
  CHECK(map.regulatory_elements[0].ref_lines == std::vector<int64_t>{-14});
  const sim::World world = worldOf(kMap);
  CHECK(world.lanes.size() == 2);
  CHECK(world.warnings.entries().empty());
  CHECK(world.stats.at("stop_lines") == 1);
}

TEST_CASE("Lanelet2 content: duplicate node, way and relation ids are refused",
          "[sim][osm][content]") {
  CHECK_THAT(refusal(with("<node id='-9'", "<node id='-8'")),
             Catch::Contains("c.osm: field 'node -8': duplicate node id"));
  CHECK_THAT(refusal(with("<way id='-15'>", "<way id='-14'>")),
             Catch::Contains("c.osm: field 'way -14': duplicate way id"));
  // A regulatory element with a lanelet's id: the lanelet's member would name two relations.
  CHECK_THAT(refusal(with("<relation id='-30'>", "<relation id='-20'>")),
             Catch::Contains("c.osm: field 'relation -20': duplicate relation id"));
}

TEST_CASE("Lanelet2 content: references to missing nodes, ways and relations are refused",
          "[sim][osm][content]") {
  CHECK_THAT(refusal(with("<nd ref='-9'/>", "<nd ref='-99'/>")),
             Catch::Contains("field 'way -15'") && Catch::Contains("node ref -99 does not exist"));
  CHECK_THAT(refusal(with("ref='-13' role='right'", "ref='-98' role='right'")),
             Catch::Contains("field 'relation -21 right'") &&
                 Catch::Contains("way ref -98 does not exist"));
  CHECK_THAT(
      refusal(with("ref='-30' role='regulatory_element'", "ref='-97' role='regulatory_element'")),
      Catch::Contains("field 'relation -21 member regulatory_element'") &&
          Catch::Contains("relation ref -97 does not exist"));
  CHECK_THAT(refusal(with("ref='-15' role='refers'", "ref='-96' role='refers'")),
             Catch::Contains("field 'relation -30 member refers'") &&
                 Catch::Contains("way ref -96 does not exist"));
  CHECK_THAT(refusal(with("ref='-14' role='ref_line'", "ref='-95' role='ref_line'")),
             Catch::Contains("field 'relation -30 member ref_line'") &&
                 Catch::Contains("way ref -95 does not exist"));
  CHECK_THAT(refusal(with("<member type='way' ref='-15' role='refers'/>",
                          "<member type='node' ref='-94' role='refers'/>")),
             Catch::Contains("field 'relation -30 member refers'") &&
                 Catch::Contains("node ref -94 does not exist"));
  // A deleted element (JOSM's action='delete') is missing too.
  CHECK_THAT(refusal(with("<relation id='-30'>", "<relation id='-30' action='delete'>")),
             Catch::Contains("relation ref -30 does not exist"));
}

TEST_CASE("Lanelet2 content: a lanelet whose left bound is its right bound is refused",
          "[sim][osm][content]") {
  CHECK_THAT(refusal(with("ref='-13' role='right'", "ref='-11' role='right'")),
             Catch::Contains("c.osm: field 'relation -21 member right'") &&
                 Catch::Contains("the right bound is way -11, the lanelet's left bound too"));
}

TEST_CASE("Lanelet2 content: coordinates outside the value bounds are refused",
          "[sim][osm][content]") {
  CHECK_THAT(refusal(with("lat='49.0001000' lon='8.4000500'", "lat='49.0001000' lon='180.5'")),
             Catch::Contains("c.osm: field 'node -5 lon'") && Catch::Contains("out of range"));
  CHECK_THAT(refusal(with("lat='49.0002100' lon='8.4000600'", "lat='-90.001' lon='8.4000600'")),
             Catch::Contains("field 'node -8 lat'") && Catch::Contains("out of range"));
  CHECK_THAT(
      refusal(
          with("<node id='-9' lat='49.0002100' lon='8.4000700'/>",
               "<node id='-9' lat='49.0002100' lon='8.4000700'><tag k='ele' v='-12001'/></node>")),
      Catch::Contains("field 'node -9 ele'") && Catch::Contains("outside"));
  // Within the degree ranges but on the other side of the Earth from the origin: beyond the
  // ENU coordinate bound of every reader of the truth, refused by the world (the InputError
  // names the way).
  const std::string antipode =
      with("lat='49.0002100' lon='8.4000700'", "lat='-49.0002100' lon='-171.6'");
  CHECK_THROWS_WITH(worldOf(antipode), Catch::Contains("c.osm: way -15 has a node at ENU") &&
                                           Catch::Contains("beyond 10000000 m"));
}

TEST_CASE("Lanelet2 content: ways whose nodes lie at one place are dropped with a warning",
          "[sim][osm][content]") {
  // The second lanelet's right bound collapses onto node -5 (both its nodes there): the
  // lanelet has no direction; dropped, the first lanelet stays.
  const sim::World w = worldOf(with("<way id='-13'><nd ref='-5'/><nd ref='-6'/>",
                                    "<way id='-13'><nd ref='-5'/><nd ref='-5'/>"));
  CHECK(w.lanes.size() == 1);
  const auto& dropped =
      w.warnings.entries().at("lanelet with a bound shorter than 0.01 m (dropped)");
  CHECK(dropped.count == 1);
  CHECK_THAT(dropped.first, Catch::Contains("c.osm: lanelet -21 (way -13, 0 m)"));
  // The same way as a lane line: no marking of no length in the truth.
  const auto& line = w.warnings.entries().at("lane or stop line way shorter than 0.01 m (dropped)");
  CHECK(line.count == 1);
  CHECK_THAT(line.first, Catch::Contains("c.osm: way -13 (line_thin)"));
  CHECK(w.stats.at("lane_lines") == 3);  // -10, -11, -12 (the base map: 4)
  CHECK(worldOf(kMap).stats.at("lane_lines") == 4);
  // A stop line of two nodes 0.7 mm apart (1e-8 degrees of longitude).
  const std::string tiny = with(
      "<way id='-14'><nd ref='-3'/><nd ref='-6'/>", "<way id='-14'><nd ref='-3'/><nd ref='-7'/>",
      with("<node id='-8'", "<node id='-7' lat='49.0002000' lon='8.40000001'/><node id='-8'"));
  const sim::World s = worldOf(tiny);
  CHECK(s.stats.at("stop_lines") == 0);
  CHECK(s.warnings.entries().at("lane or stop line way shorter than 0.01 m (dropped)").first ==
        "c.osm: way -14 (stop_line)");
  CHECK(s.lanes.size() == 2);
}
