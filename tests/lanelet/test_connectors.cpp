// Connector lanelets across unmarked stretches (lanelet/plan.cpp addConnectors).
#include <catch2/catch.hpp>

#include "lane_fixtures.hpp"
#include "mapfuse/lanelet/plan.hpp"

using namespace mapfuse;
using test::mapOf;
using test::straight;

TEST_CASE("connectors: none where the two lanelets' bounds already meet on one side", "[lanelet]") {
  // The right line runs on; the left line jumps 1.1 m across where the next instance begins.
  // A drive sample in the sliver between the two outlines asked for a connector whose right
  // bound would be a single node: in map.osm a way of one node (13 over the eight procedural
  // bench worlds at 9967aae), through which Lanelet2 routes nothing and which `simulate --map`
  // refuses ("bound way has fewer than 2 nodes").
  const VectorMap map =
      mapOf({straight(0.0, 0.0, 60.0), straight(3.5, 0.0, 29.5), straight(2.4, 30.4, 60.0)});
  const lanelet::DrivePath east = {{0.0, 1.75, 0.0}, {60.0, 1.75, 0.0}};
  const auto plan = lanelet::planLanelets(map, {east});
  REQUIRE(plan.lanelets.size() == 2);
  test::requireNoDegenerateConnector(plan);
  CHECK(plan.connectors.empty());
  CHECK(plan.one_sided_connections == 1);
}
