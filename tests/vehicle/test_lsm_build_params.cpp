// lsm-build parameters: each declared once, with bounds that refuse values which would wrap or
// exhaust memory or time, in config files and on the command line alike (issue 23).
#include <catch2/catch.hpp>
#include <set>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "sim_fixture.hpp"

using namespace mapfuse;

TEST_CASE("lsm-build parameters are declared once each", "[vehicle][config]") {
  std::set<std::string> keys;
  for (const auto& d : paramDeclarations<stages::LsmBuildParams>()) {
    INFO(d.key << " declared at " << d.file << ":" << d.line);
    CHECK(keys.insert(d.key).second);
  }
  CHECK(keys.size() == paramsToJson(stages::LsmBuildParams{}).size());
}

TEST_CASE("lsm-build refuses counts that do not fit and steps that exhaust memory",
          "[vehicle][config]") {
  auto refused = [](const nlohmann::json& j, const char* key) {
    stages::LsmBuildParams p;
    INFO(j.dump());
    CHECK_THROWS_AS(paramsFromJson(p, j, "lsm-build.json"), ConfigError);
    CHECK_THROWS_WITH(paramsFromJson(p, j, "lsm-build.json"), Catch::Contains(key));
  };
  refused({{"min_observations", 4294967301LL}}, "min_observations");  // would wrap to 5
  refused({{"min_track_frames", 4294967298LL}}, "min_track_frames");
  refused({{"point_spacing", 1e-7}}, "point_spacing");  // 10^7 points per metre of line
  refused({{"vp_window", 0}}, "vp_window");
  refused({{"mask_min_area", -1}}, "mask_min_area");
  const auto drive = test::simulatedDrive(false, false);
  const auto out = test::tempDir("lsm_build_params") / "out";
  for (const char* arg : {"--min-observations 4294967301", "--point-spacing 1e-7",
                          "--max-track-range 1e300", "--keyframe-spacing -1"}) {
    INFO(arg);
    CHECK(test::runCommand(test::appPath("lsm-build").string() + " " + drive.string() + " -o " +
                           out.string() + " -q " + arg + " 2> /dev/null") == 2);
  }
}
