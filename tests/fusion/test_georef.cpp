// georef: GPS + odometry pose graph per LSM (eq. 4-6), against the fixture's ground truth.
#include <catch2/catch.hpp>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/fusion/georef.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/stages/georef.hpp"
#include "sim_fixture.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
// Keyframe error after georef is at GPS level: the per-traversal bias (2 m) plus a margin for
// white noise and drift; never the outlier magnitude (10-20 m).
constexpr double kGpsBias = 2.0;
constexpr double kGpsLevelMargin = 1.0;                     // m
constexpr double kMaxSingleKeyframeError = kGpsBias + 2.0;  // m, no keyframe pulled by outliers
}  // namespace

TEST_CASE("georef puts keyframes at GPS level and rejects multipath fixes") {
  const auto world = test::trueWorld();
  test::FixtureOptions o;
  o.gps_bias = kGpsBias;
  o.outlier_probability = 0.1;
  int injected = 0, rejected = 0;
  for (int t = 0; t < 4; ++t) {
    const auto tr = test::makeTraversal(world, t, o);
    injected += tr.outliers;
    const auto r = fusion::georeferenceLsm(tr.lsm, test::fixtureOrigin(), {}, "fixture");
    CHECK(r.converged);
    CHECK(r.lsm.frame == LsmFrame::kEnu);
    double sum = 0, worst = 0;
    for (std::size_t k = 0; k < tr.truth.size(); ++k) {
      const double e = (r.lsm.keyframes[k].T_frame_body.translation() - tr.truth[k].translation())
                           .head<2>()
                           .norm();
      sum += e;
      worst = std::max(worst, e);
    }
    const double mean = sum / tr.truth.size();
    INFO("traversal " << t << " mean " << mean << " worst " << worst << " rejected "
                      << r.gps_rejected << " of " << tr.outliers);
    CHECK(mean < tr.gps_bias.head<2>().norm() + kGpsLevelMargin);
    CHECK(worst < kMaxSingleKeyframeError);
    CHECK(r.gps_rejected >= tr.outliers);      // every injected outlier rejected ...
    CHECK(r.gps_rejected <= tr.outliers + 2);  // ... and few good fixes with it
    rejected += r.gps_rejected;
    // elements ride their anchors: the body-frame points are untouched
    CHECK(r.lsm.elements.size() == tr.lsm.elements.size());
    CHECK(r.lsm.elements[0].points_body[0] == tr.lsm.elements[0].points_body[0]);
  }
  CHECK(injected > 0);
  CHECK(rejected >= injected);  // over all four drives too
}

TEST_CASE("georef keeps the odometry's tilt: a near-straight drive gets no spurious roll") {
  // GPS positions along a (near) line do not fix the rotation about that line; the odometry's
  // gravity (its z is up) does. Fixture odometry has exact roll / pitch, so the tilt error after
  // georef is what the GPS pose graph adds.
  constexpr double kTiltTolDeg = 0.5;  // deg, keyframe up-axis vs truth with the tilt prior
  const auto world = test::trueWorld();
  test::FixtureOptions o;
  o.gps_white = 1.5;  // m, noisy heights (and positions) as from a phone-grade receiver
  auto worstTiltDeg = [&](const fusion::GeorefSettings& s) {
    double worst = 0;
    for (int t = 0; t < 4; ++t) {
      const auto tr = test::makeTraversal(world, t, o);
      const auto r = fusion::georeferenceLsm(tr.lsm, test::fixtureOrigin(), s, "fixture");
      for (std::size_t k = 0; k < tr.truth.size(); ++k) {
        const Eigen::Vector3d up_est =
            r.lsm.keyframes[k].T_frame_body.linear().transpose() * Eigen::Vector3d::UnitZ();
        const Eigen::Vector3d up_true = tr.truth[k].linear().transpose() * Eigen::Vector3d::UnitZ();
        worst = std::max(worst, std::acos(std::min(1.0, up_est.dot(up_true))) * 180.0 / M_PI);
      }
    }
    return worst;
  };
  fusion::GeorefSettings with, without;
  without.gravity_sigma = 0;
  const double tilt_with = worstTiltDeg(with), tilt_without = worstTiltDeg(without);
  INFO("worst tilt error: with prior " << tilt_with << " deg, without " << tilt_without << " deg");
  CHECK(tilt_with < kTiltTolDeg);
  CHECK(tilt_without > 2 * kTiltTolDeg);  // the failure the prior exists for
}

TEST_CASE("georef rejects LSMs it cannot georeference") {
  const auto world = test::trueWorld();
  auto tr = test::makeTraversal(world, 0, {});
  tr.lsm.gps.clear();
  CHECK_THROWS_AS(fusion::georeferenceLsm(tr.lsm, test::fixtureOrigin(), {}, "x.json"), InputError);
  tr.lsm.keyframes.clear();
  CHECK_THROWS_AS(fusion::georeferenceLsm(tr.lsm, test::fixtureOrigin(), {}, "x.json"), InputError);
  CHECK_THROWS_AS(stages::parseOrigin("49.0,8.4"), ConfigError);
  CHECK_THROWS_AS(stages::parseOrigin("91,8.4,1"), ConfigError);
  CHECK(stages::parseOrigin("49.5,8.25,100").lon == Approx(8.25));
}

TEST_CASE("configs/georef.json mirrors GeorefParams defaults") {
  const auto j = nlohmann::json::parse(
      test::readText(std::filesystem::path(MAPFUSE_SOURCE_DIR) / "configs/georef.json"));
  CHECK(j == paramsToJson(stages::GeorefParams{}));
  CHECK_NOTHROW(validateParams(stages::GeorefParams{}));
  stages::GeorefParams bad;
  bad.georef.gravity_sigma = -0.01;
  CHECK_THROWS_AS(validateParams(bad), ConfigError);
  CHECK_THROWS_WITH(validateParams(bad), Catch::Contains("gravity_sigma"));
}

TEST_CASE("georef app: shared origin, summary, exit codes") {
  const auto dir = test::tempDir("georef_app");
  const auto world = test::trueWorld();
  for (int t = 0; t < 2; ++t)
    io::writeLsm(dir / ("t" + std::to_string(t) + ".lsm.json"),
                 test::makeTraversal(world, t, {}).lsm);
  test::writeText(dir / "list.txt",
                  (dir / "t0.lsm.json").string() + "\n" + (dir / "t1.lsm.json").string() + "\n");
  const std::string app = test::appPath("georef").string();
  REQUIRE(test::runCommand(app + " @" + (dir / "list.txt").string() + " -o " +
                           (dir / "out").string() + " --quiet") == 0);
  const Lsm a = io::readLsm(dir / "out/t0.lsm.json"), b = io::readLsm(dir / "out/t1.lsm.json");
  REQUIRE(a.origin);
  REQUIRE(b.origin);
  CHECK(a.origin->lat == b.origin->lat);
  CHECK(a.origin->lon == b.origin->lon);
  const auto summary = nlohmann::json::parse(test::readText(dir / "out/georef.summary.json"));
  CHECK(summary["lsms"].size() == 2);
  // bad LSM -> 3; unknown config key -> 2
  test::writeText(dir / "bad.lsm.json", "{\"format\": \"mapfuse.lsm\", \"version\": 1}");
  CHECK(test::runCommand(app + " " + (dir / "bad.lsm.json").string() + " -o " +
                         (dir / "out2").string() + " --quiet 2>/dev/null") == 3);
  test::writeText(dir / "cfg.json", "{\"no_such_key\": 1}");
  CHECK(test::runCommand(app + " " + (dir / "t0.lsm.json").string() + " -o " +
                         (dir / "out3").string() + " --config " + (dir / "cfg.json").string() +
                         " 2>/dev/null") == 2);
}

TEST_CASE("georef names a drive untrusted when its odometry climbs or stretches away from GPS") {
  // Issue 33: a dead reckoning that tilts (a pitched IMU, gyro-only pitch) climbs steadily away
  // from the GPS heights; a wheel scale error stretches it. The drive is then flagged
  // (trusted = false, docs/fusion.md "Trust"), never silently fused.
  constexpr double kTilt = 1.0 * M_PI / 180.0;  // rad: heights climb 1.7 % of distance
  constexpr double kStretch = 1.08;             // an 8 % wheel scale error
  const auto world = test::trueWorld();
  test::FixtureOptions o;
  o.outlier_probability = 0.0;
  o.scale_error = 0.0;
  auto tr = test::makeTraversal(world, 0, o);
  // The fixture's receiver reports 4 m vertical sigma; over its 300 m road a 1 deg climb (5 m) is
  // then within GPS noise and the fused heights follow the odometry (measured: fused minus
  // odometry slope 0.003 of the 0.017). A receiver that reports 1 m makes it visible.
  for (auto& f : tr.lsm.gps) f.sigma_v = 1.0;
  const auto good = fusion::georeferenceLsm(tr.lsm, test::fixtureOrigin(), {}, "fixture");
  INFO("good: slope " << good.odom_vertical_slope << " scale " << good.odom_scale_error
                      << " v rms " << good.residual_v_rms);
  CHECK(good.trusted);
  CHECK(std::abs(good.odom_vertical_slope) < fusion::GeorefSettings{}.trust_max_vertical_slope);

  auto tilted = tr.lsm;
  const Pose3 first = tilted.keyframes.front().T_frame_body;
  const Pose3 pitch(Eigen::AngleAxisd(-kTilt, Eigen::Vector3d::UnitY()));
  for (auto& k : tilted.keyframes) k.T_frame_body = first * pitch * first.inverse() * k.T_frame_body;
  const auto climb = fusion::georeferenceLsm(tilted, test::fixtureOrigin(), {}, "fixture");
  INFO("tilted: slope " << climb.odom_vertical_slope << " v rms " << climb.residual_v_rms);
  CHECK_FALSE(climb.trusted);
  CHECK(std::abs(climb.odom_vertical_slope) > 0.5 * std::tan(kTilt));

  auto stretched = tr.lsm;
  const Eigen::Vector3d origin = first.translation();
  for (auto& k : stretched.keyframes)
    k.T_frame_body.translation() = origin + kStretch * (k.T_frame_body.translation() - origin);
  const auto stretch = fusion::georeferenceLsm(stretched, test::fixtureOrigin(), {}, "fixture");
  INFO("stretched: scale " << stretch.odom_scale_error);
  CHECK_FALSE(stretch.trusted);
  // the fused length follows the stretched odometry in part (GPS 2.5 m sigma over 300 m): the
  // fused drive is shorter than the odometry, never longer
  CHECK(stretch.odom_scale_error < -0.01);
}
