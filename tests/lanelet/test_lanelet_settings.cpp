#include <catch2/catch.hpp>

#include "mapfuse/lanelet/regulatory.hpp"

using namespace mapfuse;
using Vec3 = Eigen::Vector3d;

namespace {

/// Two straight lane lines along x, `width` apart, `length` long, a stop line across their end
/// and a traffic light `light_x` beyond it: one lanelet whose direction only the stop line gives.
VectorMap straightLane(double width, double length, double light_x) {
  VectorMap map;
  auto line = [&](double y) {
    MapInstance m;
    m.id = static_cast<int64_t>(map.instances.size() + 1);
    for (double x = 0; x <= length + 1e-9; x += 1.0) m.points.push_back({x, y, 0});
    map.instances.push_back(m);
  };
  line(0.0);
  line(width);
  MapInstance stop;
  stop.id = 10;
  stop.cls = CrowdClass::kStopLine;
  stop.points = {{length - 2.0, 0.3, 0}, {length - 2.0, width - 0.3, 0}};
  map.instances.push_back(stop);
  MapInstance light;
  light.id = 11;
  light.cls = CrowdClass::kTrafficLight;
  light.points = {{length - 2.0 + light_x, 0.5 * width, 5.0}};
  light.height = 1.0;
  map.instances.push_back(light);
  return map;
}

}  // namespace

TEST_CASE("LaneletSettings: lane width, length and reaches decide the plan", "[lanelet]") {
  const lanelet::LaneletSettings defaults;
  // A 3.5 m lane, 30 m long, its light 20 m past the stop line: one lanelet, oriented towards
  // the stop line (x rising), the light tied to that stop line.
  const VectorMap map = straightLane(3.5, 30.0, 20.0);
  const auto plan = lanelet::planExport(map, {}, defaults);
  REQUIRE(plan.lanes.lanelets.size() == 1);
  const auto& ll = plan.lanes.lanelets.front();
  CHECK(ll.direction_known);
  CHECK(ll.centre.back().x() > ll.centre.front().x());
  REQUIRE(plan.stop_lines.size() == 1);
  CHECK(plan.stop_lines[0].lanelets == std::vector<std::size_t>{0});
  REQUIRE(plan.devices.size() == 1);
  CHECK(plan.devices[0].stop == 0);

  SECTION("a lane wider than lanelet_max_width bounds no lanelet") {
    lanelet::LaneletSettings s;
    s.max_width = 3.0;
    CHECK(lanelet::planExport(map, {}, s).lanes.lanelets.empty());
  }
  SECTION("a lane narrower than lanelet_min_width bounds no lanelet") {
    lanelet::LaneletSettings s;
    s.min_width = 4.0;
    CHECK(lanelet::planExport(map, {}, s).lanes.lanelets.empty());
  }
  SECTION("lines shorter than lanelet_min_length bound no lanelet") {
    lanelet::LaneletSettings s;
    s.min_length = 31.0;
    CHECK(lanelet::planExport(map, {}, s).lanes.lanelets.empty());
  }
  SECTION("a stop line farther than lanelet_stop_line_end from the end orients nothing") {
    lanelet::LaneletSettings s;
    s.stop_line_end = 1.0;  // the stop line stands 2 m before the end
    const auto p = lanelet::planExport(map, {}, s);
    REQUIRE(p.lanes.lanelets.size() == 1);
    CHECK_FALSE(p.lanes.lanelets[0].direction_known);
  }
  SECTION("a light beyond lanelet_regulatory_reach serves no stop line") {
    lanelet::LaneletSettings s;
    s.regulatory_reach = 15.0;  // the light stands 20 m from the stop line's middle
    const auto p = lanelet::planExport(map, {}, s);
    REQUIRE(p.devices.size() == 1);
    CHECK(p.devices[0].stop == -1);
  }
}
