// lsm-build states how far its ego-motion agrees with the drive's GPS, per axis (issue 33,
// "never silently wrong at frames level"): the injected faults of the trust tests are measured
// by the first stage already, against the simulator's known injections.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "mapfuse/stages/lsm_build.hpp"
#include "mapfuse/vehicle/lsm_build.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
constexpr double kWheelScale = 0.03;        // injected: the wheel reads 3 % fast
constexpr double kScaleTol = 0.01;          // measured scale error vs the injection
constexpr double kSoundScaleMax = 0.01;     // |scale error| of a sound drive (wheel sigma 0.005)
constexpr double kSoundSlopeMax = 0.002;    // |height slope| of a sound drive on hills
constexpr double kPitchedSlopeMin = 0.005;  // a 0.5° pitched IMU (0.0087 rad) climbs or sinks

geo::TrackAgreement agreementOf(const fs::path& frames, const std::string& drive) {
  stages::LsmBuildParams p;
  stages::LsmBuildInputs in;
  in.drive = frames / drive;
  return vehicle::egoMotionAgainstGps(stages::loadDrive(in, p));
}
}  // namespace

TEST_CASE("lsm-build: ego-motion against GPS names a wheel scale error and a pitched IMU") {
  // Three 1.2 km outward drives on the 5 % hilly world: 0 sound, 1 with its wheel 3 % fast, 2
  // with its IMU mounted pitched by 0.5°.
  const fs::path out = test::tempDir("ego_motion_gps");
  const std::string cmd =
      test::appPath("simulate").string() + " -q -o " + out.string() +
      " --level frames --frames-masks 0 --traversals 3 --vehicles 3 --routes 1 --seed 5 "
      "--world-grid-size 9 --world-hill-grade 0.05 --route-outward 1 --route-length 1200 "
      "--inject-wheel-traversal 1 --inject-wheel-scale " +
      std::to_string(kWheelScale) + " --inject-pitch-traversal 2 > /dev/null";
  REQUIRE(test::runCommand(cmd) == 0);
  const auto sound = agreementOf(out / "frames", "veh00_trav000");
  const auto wheel = agreementOf(out / "frames", "veh01_trav001");
  const auto pitched = agreementOf(out / "frames", "veh02_trav002");
  INFO("scale error sound / wheel / pitched: " << sound.scale_error << " / " << wheel.scale_error
                                               << " / " << pitched.scale_error);
  INFO("height slope sound / wheel / pitched: "
       << sound.vertical_slope << " / " << wheel.vertical_slope << " / " << pitched.vertical_slope);
  INFO("horizontal RMS sound " << sound.horizontal_rms << " m, vertical RMS " << sound.vertical_rms
                               << " m over " << sound.samples << " fixes");
  REQUIRE(sound.samples > 60);
  CHECK(std::abs(sound.scale_error) < kSoundScaleMax);
  CHECK(std::abs(sound.vertical_slope) < kSoundSlopeMax);
  // a wheel reading 3 % fast makes the odometry 3 % long: GPS over odometry is 1/1.03
  CHECK(wheel.scale_error == Approx(1.0 / (1.0 + kWheelScale) - 1.0).margin(kScaleTol));
  CHECK(std::abs(pitched.vertical_slope) > kPitchedSlopeMin);
}
