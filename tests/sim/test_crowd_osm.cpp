// Lanelet2 OSM reader and the World built from it (tests for issue 3, simulate).
#include <Eigen/Core>
#include <catch2/catch.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/lanelet2_osm.hpp"
#include "mapfuse/sim/lanelet2_world.hpp"
#include "sim/sign_posts.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr const char* kKarlsruhe = "data/maps/lanelet2_karlsruhe_mapping_example.osm";

/// Two lanelets in a row (negative ids, as JOSM writes new elements), one unknown way type,
/// one relation of an unknown type, a lanelet without optional tags.
const char* kSmallMap = R"(<?xml version='1.0' encoding='UTF-8'?>
<osm version='0.6' generator='test'>
  <node id='-1' lat='49.0000000' lon='8.4000000'/>
  <node id='-2' lat='49.0001000' lon='8.4000000'/>
  <node id='-3' lat='49.0002000' lon='8.4000000'/>
  <node id='-4' lat='49.0000000' lon='8.4000500'/>
  <node id='-5' lat='49.0001000' lon='8.4000500'/>
  <node id='-6' lat='49.0002000' lon='8.4000500'/>
  <node id='-7' lat='49.0001000' lon='8.4001000'><tag k='ele' v='2.5'/></node>
  <way id='-10'><nd ref='-1'/><nd ref='-2'/><tag k='type' v='line_thin'/><tag k='subtype' v='dashed'/></way>
  <way id='-11'><nd ref='-2'/><nd ref='-3'/><tag k='type' v='line_thin'/><tag k='subtype' v='solid'/></way>
  <way id='-12'><nd ref='-4'/><nd ref='-5'/><tag k='type' v='curbstone'/></way>
  <way id='-13'><nd ref='-5'/><nd ref='-6'/><tag k='type' v='road_border'/></way>
  <way id='-14'><nd ref='-2'/><nd ref='-5'/><tag k='type' v='stop_line'/></way>
  <way id='-15'><nd ref='-5'/><nd ref='-7'/><tag k='type' v='hedge_of_mystery'/></way>
  <way id='-16'><nd ref='-6'/><nd ref='-7'/></way>
  <relation id='-20'><member type='way' ref='-10' role='left'/><member type='way' ref='-12' role='right'/>
    <tag k='type' v='lanelet'/><tag k='subtype' v='road'/></relation>
  <relation id='-21'><member type='way' ref='-11' role='left'/><member type='way' ref='-13' role='right'/>
    <tag k='type' v='lanelet'/></relation>
  <relation id='-22'><member type='way' ref='-15' role='outer'/><tag k='type' v='multipolygon'/></relation>
</osm>
)";

template <class F>
std::string parseErrorOf(F&& f) {
  try {
    f();
  } catch (const ParseError& e) {
    return e.what();
  }
  return "(no ParseError)";
}
}  // namespace

TEST_CASE("Lanelet2: Karlsruhe example map counts", "[sim][osm]") {
  const auto path = test::requireShared(kKarlsruhe);
  const io::Lanelet2Map map = io::readLanelet2Osm(path);
  CHECK(map.lanelets.size() == 371);
  CHECK(map.countWays("stop_line") == 28);
  CHECK(map.countWays("traffic_sign") == 11);
  CHECK(map.countWays("traffic_light") == 10);
  CHECK(map.node_count == 2258);
  // Every way type of this real map is one of Lanelet2's tagging spec (bike_marking, fence,
  // guard_rail, keepout, rail, symbol, wall, zig-zag... included); every way has a type.
  for (const auto& [type, n] : map.skipped_way_types) FAIL_CHECK(type << ": " << n << " skipped");
  CHECK(map.untyped_ways == 0);
  REQUIRE(map.first_node);
  CHECK(map.first_node->lat == Approx(49.00345654351).margin(1e-11));

  const sim::World world = sim::worldFromLanelet2(map, *map.first_node);
  std::map<CrowdClass, int> count;
  for (const auto& m : world.truth.instances) ++count[m.cls];
  CHECK(count[CrowdClass::kStopLine] == 28);
  CHECK(count[CrowdClass::kTrafficSign] == 11);
  CHECK(count[CrowdClass::kTrafficLight] == 10);
  CHECK(count[CrowdClass::kCrosswalk] == 8);
  // Placed under the signs and lights: 21 of them on 15 posts (six mounted 0.2-0.6 m beside
  // another share its post). Every sign and light stands on one; no two posts closer than 1 m.
  CHECK(count[CrowdClass::kPole] == 15);
  std::vector<Eigen::Vector2d> poles;
  for (const auto& m : world.truth.instances)
    if (m.cls == CrowdClass::kPole) poles.push_back(m.points.front().head<2>());
  for (std::size_t i = 0; i < poles.size(); ++i)
    for (std::size_t j = i + 1; j < poles.size(); ++j)
      CHECK((poles[i] - poles[j]).norm() >= sim::kSharedPostRadius);
  for (const auto& m : world.truth.instances) {
    if (m.cls != CrowdClass::kTrafficSign && m.cls != CrowdClass::kTrafficLight) continue;
    Eigen::Vector2d base = Eigen::Vector2d::Zero();
    for (const auto& p : m.points) base += p.head<2>();
    base /= double(m.points.size());
    double nearest = 1e9;
    for (const auto& q : poles) nearest = std::min(nearest, (q - base).norm());
    CHECK(nearest < sim::kSharedPostRadius);
  }
  CHECK(count[CrowdClass::kGroundArrow] > 0);
  // The lane graph is connected: most lanes have a successor.
  int with_successor = 0;
  for (const auto& l : world.lanes) with_successor += !l.successors.empty();
  CHECK(with_successor > 0.8 * world.lanes.size());
}

TEST_CASE("Lanelet2: negative ids, missing optional tags and unknown types load", "[sim][osm]") {
  const io::Lanelet2Map map = io::parseLanelet2Osm(kSmallMap, "small.osm");
  REQUIRE(map.lanelets.size() == 2);
  CHECK(map.lanelets[0].id == -20);
  CHECK(map.lanelets[1].subtype.empty());
  CHECK(map.lanelets[1].one_way);
  CHECK(map.skipped_way_types.at("hedge_of_mystery") == 1);
  // A way without `type` is a `virtual` bound (CommonRoad conversions write them), not skipped.
  CHECK(map.skipped_way_types.count("(none)") == 0);
  CHECK(map.untyped_ways == 1);
  CHECK(map.way(-16)->type == "virtual");
  CHECK(map.way(-16)->untyped);
  CHECK(map.skipped_relation_types.at("multipolygon") == 1);
  CHECK(map.way(-15)->points[1].alt == 2.5);

  const sim::World world = sim::worldFromLanelet2(map, *map.first_node);
  REQUIRE(world.lanes.size() == 2);
  // Both bounds run north; the left bound (x = 8.4) is west, so the lanes drive north and the
  // first connects to the second through the shared end nodes.
  CHECK(world.lanes[0].centerline.back().y() > world.lanes[0].centerline.front().y());
  REQUIRE(world.lanes[0].successors.size() == 1);
  CHECK(world.lanes[0].successors[0] == 1);
  int lines = 0, stops = 0;
  for (const auto& m : world.truth.instances) {
    lines += m.cls == CrowdClass::kLaneLine;
    stops += m.cls == CrowdClass::kStopLine;
  }
  CHECK(lines == 2);
  CHECK(stops == 1);
  CHECK(world.stats.at("skipped_ways") == 1);
  CHECK(world.stats.at("untyped_ways_as_virtual") == 1);
}

TEST_CASE("Lanelet2: malformed maps are ParseErrors naming file and element", "[sim][osm]") {
  const std::string good = kSmallMap;
  // Truncated XML.
  CHECK_THAT(parseErrorOf([&] { io::parseLanelet2Osm(good.substr(0, good.size() / 2), "t.osm"); }),
             Catch::Contains("t.osm") && Catch::Contains("XML"));
  // A way referring to a node that does not exist.
  std::string missing = good;
  missing.replace(missing.find("<nd ref='-3'/>"), 14, "<nd ref='-99'/>");
  CHECK_THAT(parseErrorOf([&] { io::parseLanelet2Osm(missing, "m.osm"); }),
             Catch::Contains("m.osm") && Catch::Contains("way -11") && Catch::Contains("-99"));
  // A latitude that is not a number / out of range.
  std::string bad_lat = good;
  bad_lat.replace(bad_lat.find("lat='49.0001000' lon='8.4000000'"), 16, "lat='north'");
  CHECK_THAT(parseErrorOf([&] { io::parseLanelet2Osm(bad_lat, "b.osm"); }),
             Catch::Contains("b.osm") && Catch::Contains("node -2 lat"));
  std::string far_lat = good;
  far_lat.replace(far_lat.find("lat='49.0001000' lon='8.4000000'"), 16, "lat='91.00000'");
  CHECK_THAT(parseErrorOf([&] { io::parseLanelet2Osm(far_lat, "f.osm"); }),
             Catch::Contains("node -2 lat") && Catch::Contains("out of range"));
  // A lanelet bound that does not exist.
  std::string no_bound = good;
  no_bound.replace(no_bound.find("ref='-13' role='right'"), 9, "ref='-77'");
  CHECK_THAT(parseErrorOf([&] { io::parseLanelet2Osm(no_bound, "n.osm"); }),
             Catch::Contains("relation -21"));
  // A tag value that is not UTF-8 (the OpenDRIVE reader's finding of issue 37; both XML
  // readers share the check).
  std::string latin = good;
  latin.replace(latin.find("v='dashed'"), 10, "v='dash\xe9'");
  CHECK_THAT(parseErrorOf([&] { io::parseLanelet2Osm(latin, "l.osm"); }),
             Catch::Contains("l.osm") && Catch::Contains("field 'tag@v': text that is not UTF-8"));
  // Missing file: IoError.
  CHECK_THROWS_AS(io::readLanelet2Osm("/nonexistent/map.osm"), IoError);
}

TEST_CASE("Lanelet2: ids near the int64 limits and 1000 km of lanes are refused",
          "[sim][osm][bounds]") {
  // Fuzz findings (fuzz_lanelet2_osm). Ids near INT64_MAX overflowed the simulator's id
  // allocator (max id + 1), and std::abs(INT64_MIN); one node 2700 km from the rest made a lane
  // of 5.4 million centreline samples and a 30 s run: now an InputError naming the file.
  std::string huge_id = kSmallMap;  // 2^63 - 2^32 + 1
  huge_id.replace(huge_id.find("id='-16'"), 8, "id='9223372032559808512'");
  CHECK_THAT(parseErrorOf([&] { io::parseLanelet2Osm(huge_id, "h.osm"); }),
             Catch::Contains("h.osm") && Catch::Contains("9223372032559808512") &&
                 Catch::Contains("2^63"));
  std::string min_id = kSmallMap;
  min_id.replace(min_id.find("id='-16'"), 8, "id='-9223372036854775808'");
  CHECK_THAT(parseErrorOf([&] { io::parseLanelet2Osm(min_id, "n.osm"); }),
             Catch::Contains("-9223372036854775808"));
  // The largest allowed id (the Karlsruhe map has ids up to 9.217e18) converts.
  std::string edge_id = kSmallMap;
  edge_id.replace(edge_id.find("id='-10'"), 8, "id='9223372032559808511'");
  edge_id.replace(edge_id.find("ref='-10'"), 9, "ref='9223372032559808511'");
  const io::Lanelet2Map edge = io::parseLanelet2Osm(edge_id, "e.osm");
  CHECK(sim::worldFromLanelet2(edge, *edge.first_node).lanes.size() == 2);

  std::string far = kSmallMap;
  far.replace(far.find("lat='49.0002000' lon='8.4000000'"), 16, "lat='25.0002000'");
  const io::Lanelet2Map map = io::parseLanelet2Osm(far, "far.osm");
  try {
    sim::worldFromLanelet2(map, *map.first_node);
    FAIL("a 2700 km lane was sampled");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains("far.osm") && Catch::Contains("km"));
  }
}

TEST_CASE("Lanelet2: a lanelet whose bounds lie 100 km apart is refused", "[sim][osm][bounds]") {
  // Fuzz finding (fuzz_lanelet2_osm, second 10-minute run): one node of a right bound 730 km
  // east of the rest made a lanelet 365 km wide on average, whose centreline ran far from both
  // bounds; simulate then drove it for hours (44 s, 2.9 GB per run). Now an InputError naming
  // the file, the lanelet and its two ways.
  std::string wide = kSmallMap;
  wide.replace(wide.find("lat='49.0000000' lon='8.4000500'"), 32,
               "lat='49.0000000' lon='18.4000500'");
  const io::Lanelet2Map map = io::parseLanelet2Osm(wide, "wide.osm");
  try {
    sim::worldFromLanelet2(map, *map.first_node);
    FAIL("a lanelet 365 km wide was accepted");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()),
               Catch::Contains("wide.osm") && Catch::Contains("lanelet -20") &&
                   Catch::Contains("-10") && Catch::Contains("-12") && Catch::Contains("m apart"));
  }
}
