#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/eval/trajectory_metrics.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::eval;

namespace {
constexpr double kExact = 1e-9;

TrueTrajectory straightTruth() {
  TrueTrajectory t;
  t.drive_id = "d0";
  t.origin = {49.0, 8.4, 110.0};
  for (int i = 0; i < 11; ++i)
    t.poses.push_back({i, double(i), poseFromXyzRpy(5.0 * i, 0, 0, 0, 0, 0)});
  return t;
}

Lsm estimate(const TrueTrajectory& t, double dy) {
  Lsm lsm;
  lsm.drive_id = t.drive_id;
  lsm.frame = LsmFrame::kEnu;
  lsm.origin = t.origin;
  for (const auto& p : t.poses) {
    Keyframe k;
    k.id = p.id;
    k.stamp = p.stamp;
    k.T_frame_body = p.T_enu_body;
    k.T_frame_body.translation().y() += dy;
    lsm.keyframes.push_back(k);
  }
  return lsm;
}
}  // namespace

TEST_CASE("a constant offset is all ATE and no RPE", "[eval][trajectory]") {
  const auto truth = straightTruth();
  const auto m = compareTrajectory(estimate(truth, 0.2), truth, 10.0, "est.cbor");
  CHECK(m.matched == 11);
  CHECK(m.ate_translation.mean == Approx(0.2).margin(kExact));
  CHECK(m.ate_rotation.max == Approx(0.0).margin(kExact));
  CHECK(m.rpe_translation.count == 9);  // pairs (i, i + 2): 10 m apart
  CHECK(m.rpe_translation.max == Approx(0.0).margin(kExact));
}

TEST_CASE("a linear drift shows as relative error per distance", "[eval][trajectory]") {
  const auto truth = straightTruth();
  Lsm est = estimate(truth, 0.0);
  for (auto& k : est.keyframes) k.T_frame_body.translation().y() += 0.01 * double(k.id);
  const auto m = compareTrajectory(est, truth, 10.0, "est.cbor");
  CHECK(m.rpe_translation.mean == Approx(0.02).margin(kExact));  // 2 keyframes per 10 m
  CHECK(m.ate_translation.max == Approx(0.1).margin(kExact));
}

TEST_CASE("trajectory inputs are checked", "[eval][trajectory]") {
  const auto truth = straightTruth();
  Lsm est = estimate(truth, 0.0);
  est.frame = LsmFrame::kOdom;
  CHECK_THROWS_AS(compareTrajectory(est, truth, 10.0, "x"), InputError);
  est = estimate(truth, 0.0);
  est.origin->lat = 95.0;  // not a WGS84 point: no conversion possible
  CHECK_THROWS_AS(compareTrajectory(est, truth, 10.0, "x"), InputError);
  est = estimate(truth, 0.0);
  for (auto& k : est.keyframes) k.stamp += 1000.0;  // after the truth ends
  CHECK_THROWS_AS(compareTrajectory(est, truth, 10.0, "x"), InputError);
}

TEST_CASE("true trajectory files are read strictly", "[eval][trajectory]") {
  const auto dir = test::tempDir("eval-traj");
  nlohmann::json j = {
      {"format", "mapfuse.trajectory"},
      {"version", 1},
      {"drive_id", "d0"},
      {"vehicle_id", "v"},
      {"frame", "enu"},
      {"origin", io::originToJson({49.0, 8.4, 110.0})},
      {"poses", {{{"id", 0}, {"stamp", 0.0}, {"pose", io::poseToJson(Pose3::Identity())}}}}};
  io::writeDocument(dir / "d0.trajectory.json", j);
  const auto t = readTrueTrajectory(dir / "d0.trajectory.json");
  CHECK(t.poses.size() == 1);
  j["poses"][0].erase("stamp");
  io::writeDocument(dir / "bad.trajectory.json", j);
  try {
    readTrueTrajectory(dir / "bad.trajectory.json");
    FAIL("missing stamp accepted");
  } catch (const ParseError& e) {
    CHECK_THAT(e.what(), Catch::Contains("bad.trajectory.json"));
    CHECK_THAT(e.field(), Catch::Contains("stamp"));
  }
}

TEST_CASE("a truth about another origin is converted, not refused", "[eval][trajectory]") {
  constexpr double kConversion = 1e-6;  // m, deg: WGS84 round trip
  const auto truth = straightTruth();
  Lsm est = estimate(truth, 0.0);
  est.origin = geo::LatLonAlt{49.002, 8.403, 115.0};  // ~300 m away: the same poses about it
  const geo::EnuConverter from(truth.origin), to(*est.origin);
  for (auto& k : est.keyframes) k.T_frame_body = geo::reexpressPose(k.T_frame_body, from, to);
  const auto m = compareTrajectory(est, truth, 10.0, "est.cbor");
  CHECK(m.matched == 11);
  CHECK(m.ate_translation.max == Approx(0.0).margin(kConversion));
  CHECK(m.ate_rotation.max == Approx(0.0).margin(kConversion));
  CHECK(m.rpe_translation.max == Approx(0.0).margin(kConversion));
}

TEST_CASE("keyframes are matched by stamp and the truth is interpolated between its poses",
          "[eval][trajectory]") {
  // lsm-build picks its own keyframes from raw frames: other ids, stamps between true poses.
  const auto truth = straightTruth();  // 5 m per second along x
  Lsm est = estimate(truth, 0.0);
  est.keyframes.clear();
  for (int i = 0; i < 8; ++i) {
    Keyframe k;
    k.id = 100 + i;
    k.stamp = 0.25 + 1.3 * i;
    k.T_frame_body = poseFromXyzRpy(5.0 * k.stamp, 0, 0, 0, 0, 0);
    est.keyframes.push_back(k);
  }
  const auto m = compareTrajectory(est, truth, 10.0, "est.cbor");
  CHECK(m.matched == 8);
  CHECK(m.ate_translation.max == Approx(0.0).margin(kExact));
  Keyframe late = est.keyframes.back();
  late.stamp = 10.5;  // beyond the last true pose (stamp 10): not matched
  est.keyframes.push_back(late);
  CHECK(compareTrajectory(est, truth, 10.0, "est.cbor").matched == 8);
}
