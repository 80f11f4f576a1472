// simulate and simulate-lidar parameters: each declared once, with bounds that refuse values
// which would wrap or exhaust memory or time, in config files and on the command line (issue 23).
#include <catch2/catch.hpp>
#include <set>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/stages/simulate.hpp"
#include "mapfuse/stages/simulate_lidar.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
template <class Params>
void checkDeclaredOnce() {
  std::set<std::string> keys;
  for (const auto& d : paramDeclarations<Params>()) {
    INFO(d.key << " declared at " << d.file << ":" << d.line);
    CHECK(keys.insert(d.key).second);
  }
  CHECK(keys.size() == paramsToJson(Params{}).size());
}

template <class Params>
void refused(const nlohmann::json& j, const char* key) {
  Params p;
  INFO(j.dump());
  CHECK_THROWS_AS(paramsFromJson(p, j, "params.json"), ConfigError);
  CHECK_THROWS_WITH(paramsFromJson(p, j, "params.json"), Catch::Contains(key));
}

template <class Params>
void refusedRelation(const nlohmann::json& j, const char* key) {
  Params p;
  INFO(j.dump());
  paramsFromJson(p, j, "params.json");
  CHECK_THROWS_AS(validateParams(p), ConfigError);
  CHECK_THROWS_WITH(validateParams(p), Catch::Contains(key));
}
}  // namespace

TEST_CASE("simulate parameters are declared once each", "[sim][config]") {
  checkDeclaredOnce<stages::SimulateParams>();
  checkDeclaredOnce<stages::SimulateLidarParams>();
}

TEST_CASE("simulate refuses counts that do not fit and sizes that exhaust memory",
          "[sim][config]") {
  using P = stages::SimulateParams;
  refused<P>({{"traversals", 4294967301LL}}, "traversals");  // would wrap to 5
  refused<P>({{"camera_width", 1000000}}, "camera_width");
  refused<P>({{"imu_rate", 1e9}}, "imu_rate");
  refused<P>({{"world_grid_size", 100000}}, "world_grid_size");
  refused<P>({{"point_spacing", 1e-9}}, "point_spacing");
  // 2e6 km at 0.6 m/s: 3e11 IMU samples in one drive
  refusedRelation<P>({{"route_length", 1e6}, {"speed_min", 0.6}}, "route_length");
  refusedRelation<P>({{"camera_rate", 30.0}}, "camera_rate");  // does not divide imu_rate
  const auto dir = test::tempDir("simulate_params");
  for (const char* arg :
       {"--traversals 4294967301", "--camera-height 100000", "--route-length 1e300"}) {
    INFO(arg);
    CHECK(test::runCommand(test::appPath("simulate").string() + " -q -o " + (dir / "o").string() +
                           " " + arg + " 2> /dev/null") == 2);
  }
  CHECK_FALSE(std::filesystem::exists(dir / "o"));
}

TEST_CASE("simulate-lidar refuses counts that do not fit and sizes that exhaust memory",
          "[sim][config]") {
  using P = stages::SimulateLidarParams;
  refused<P>({{"frames", 4294967301LL}}, "frames");  // would wrap to 5
  refused<P>({{"azimuth_steps", 100000000}}, "azimuth_steps");
  refused<P>({{"confusion_scale", 1e-9}}, "confusion_scale");
  refused<P>({{"pole_spacing", 1e-6}}, "pole_spacing");
  refused<P>({{"date", "2011-09-26"}}, "date");
  refusedRelation<P>({{"lidar_min_range", 200.0}}, "lidar_min_range");
  refusedRelation<P>({{"start_time", 86399.0}}, "start_time");
  const auto dir = test::tempDir("simulate_lidar_params");
  for (const char* arg : {"--frames 4294967301", "--bleed-sigma 1e6", "--drive a/b"}) {
    INFO(arg);
    CHECK(test::runCommand(test::appPath("simulate-lidar").string() + " -q -o " +
                           (dir / "o").string() + " " + arg + " 2> /dev/null") == 2);
  }
  CHECK_FALSE(std::filesystem::exists(dir / "o"));
}
